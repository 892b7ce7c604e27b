// OFF (Geomview's Object File Format), ASCII: OFF, COFF, NOFF and CNOFF/NCOFF with '#' comments,
// one vertex or face per line. Our own parser: CGAL's reader (CGAL is a dependency of the core)
// reads into its own mesh types and reports failure as a bool, without the line at fault, and the
// colour rule below needs the numbers as written.
//
// Colour rule. OFF does not say whether colour components are 8-bit integers (0-255) or floats in
// [0, 1], so it is decided per file, separately for vertex and for face colours: they are 8-bit if
// every component is written as an integer ("255", not "255.0") or if any component exceeds 1;
// otherwise they are floats in [0, 1]. Every component must lie in [0, 255]. Colours are stored
// normalised to [0, 1]; their type is uint8 for 8-bit colours that are all whole numbers, float32
// otherwise. The writer therefore writes float colours with a decimal point ("1.0", never "1").
//
// Vertex alpha becomes the vertex property "alpha", face colours the face properties "red",
// "green", "blue" (and "alpha"), as PLY names them; they are kept only when every element has them.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "io/formats.h"

namespace rangefill::detail {

namespace {

constexpr std::array<const char*, 4> kColourNames = {"red", "green", "blue", "alpha"};

bool is_integer_token(std::string_view token) {
  const size_t digits = !token.empty() && (token[0] == '+' || token[0] == '-') ? 1 : 0;
  return token.size() > digits && token.find_first_not_of("0123456789", digits) == token.npos;
}

// The colour components of all vertices or all faces (one entry per triangle), kept as written
// until the whole file is read and the colour rule can be applied.
struct ColourColumn {
  std::vector<std::array<float, 4>> components;  // r g b a; 0 where absent
  long long with_rgb = 0;                        // elements of the file that have r g b
  long long with_alpha = 0;                      // ... and a
  bool integer_tokens = true;
  bool whole_numbers = true;
  float max_component = 0;

  bool eight_bit() const { return integer_tokens || max_component > 1; }
  ScalarType type() const {
    return eight_bit() && whole_numbers ? ScalarType::uint8 : ScalarType::float32;
  }
  float normalised(size_t element, int component) const {
    const float value = components[element][component];
    return eight_bit() ? static_cast<float>(value * (1.0 / 255.0)) : value;
  }
  // An extra property of type() holds the 8-bit value itself, a float one the normalised value.
  ExtraProperty property(int component) const {
    ExtraProperty result{kColourNames[component], type(), {}};
    result.values.reserve(components.size());
    for (size_t i = 0; i < components.size(); ++i) {
      result.values.push_back(type() == ScalarType::uint8 ? components[i][component]
                                                          : normalised(i, component));
    }
    return result;
  }
};

class OffParser {
 public:
  OffParser(std::string_view bytes, const std::string& name)
      : bytes_(bytes), reader_(bytes), name_(name) {}

  ReadResult parse() {
    read_header();
    read_vertices();
    read_faces();
    store_colours();
    Mesh& mesh = result_.mesh;
    mesh.storage.position = ScalarType::float64;
    mesh.storage.normal = ScalarType::float64;
    mesh.vertex_hole.reserve(mesh.positions.size());
    mesh.vertex_hole.assign(mesh.positions.size(), kOriginal);
    return std::move(result_);
  }

 private:
  // Splits the next non-empty line into tokens_; false at the end of the file.
  bool next_line() {
    if (!reader_.next_line()) return false;
    tokens_.clear();
    for (std::string_view token = reader_.token(); !token.empty(); token = reader_.token()) {
      tokens_.push_back(token);
    }
    return true;
  }

  [[noreturn]] void fail_here(const std::string& what) const {
    fail_at(name_, reader_.line_number(), what);
  }

  template <typename T>
  T number(std::string_view token) const {
    return parse_number_at<T>(token, name_, reader_.line_number());
  }

  void read_header() {
    if (!next_line()) fail(name_, "file is empty (no OFF header)");
    std::vector<std::string_view> counts = tokens_;
    const std::string_view first = tokens_.front();
    const size_t keyword_end = first.find("OFF");
    if (keyword_end == first.npos) {
      // The keyword is optional in Geomview's OFF; the counts then come first.
      long long count = 0;
      if (!parse_number(first, count)) {
        fail_here("not an OFF file: it starts with " + quote(first) + ", not the keyword OFF");
      }
    } else {
      const std::string_view prefix = first.substr(0, keyword_end);
      keyword_ = first.substr(0, keyword_end + 3);
      if (prefix.find_first_of("ST4n") != prefix.npos) {
        fail_here(quote(keyword_) + " files (texture coordinates, homogeneous or n-dimensional " +
                  "vertices) are not supported");
      }
      if (!prefix.empty() && prefix != "C" && prefix != "N" && prefix != "CN" && prefix != "NC") {
        fail_here("not an OFF file: unknown keyword " + quote(first));
      }
      colours_ = prefix.find('C') != prefix.npos;
      normals_ = prefix.find('N') != prefix.npos;
      counts.erase(counts.begin());
      // Some files (ModelNet's) glue the counts to the keyword: "OFF490 518 0".
      const std::string_view glued = first.substr(keyword_end + 3);
      if (!glued.empty()) counts.insert(counts.begin(), glued);
      if (!counts.empty() && counts.front() == "BINARY") {
        fail_here("binary OFF is not supported; convert the file to ASCII OFF");
      }
      if (counts.empty()) {
        if (!next_line()) fail(name_, "file ends after the OFF keyword");
        counts = tokens_;
      }
    }
    if (counts.size() != 2 && counts.size() != 3) {
      fail_here("expected the counts 'vertices faces edges', found " +
                std::to_string(counts.size()) + " values");
    }
    vertex_count_ = number<long long>(counts[0]);
    face_count_ = number<long long>(counts[1]);
    if (counts.size() == 3) number<long long>(counts[2]);  // edges: unused, but must be a number
    if (vertex_count_ < 0 || face_count_ < 0) fail_here("negative vertex or face count");

    // Before anything is reserved: each vertex line holds at least "x y z\n" (6 bytes) and each
    // face line "3 a b c\n" (8 bytes); the last line may lack its '\n'.
    const auto remaining = static_cast<unsigned long long>(bytes_.size() - reader_.offset());
    const auto vertices = static_cast<unsigned long long>(vertex_count_);
    const auto faces = static_cast<unsigned long long>(face_count_);
    if (vertices > remaining || faces > remaining || 6 * vertices + 8 * faces > remaining + 1) {
      fail(name_, "the header declares " + std::to_string(vertex_count_) + " vertices and " +
                      std::to_string(face_count_) + " faces, more than the remaining " +
                      std::to_string(remaining) + " bytes can hold (truncated file or bad header)");
    }
    if (vertex_count_ > std::numeric_limits<int>::max()) {
      fail(name_, "too many vertices for 32-bit indices");
    }
  }

  void read_vertices() {
    Mesh& mesh = result_.mesh;
    const size_t colour_start = normals_ ? 6 : 3;
    const std::string layout =
        std::string("x y z") + (normals_ ? " nx ny nz" : "") + (colours_ ? " r g b [a]" : "");
    mesh.positions.reserve(vertex_count_);
    if (normals_) mesh.normals.reserve(vertex_count_);
    if (colours_) vertex_colours_.components.reserve(vertex_count_);
    for (long long v = 0; v < vertex_count_; ++v) {
      if (!next_line()) {
        fail(name_, "file ends after " + std::to_string(v) + " of the " +
                        std::to_string(vertex_count_) + " vertices the header declares");
      }
      const size_t colour_values = tokens_.size() - std::min(tokens_.size(), colour_start);
      const bool valid_count =
          tokens_.size() >= colour_start &&
          (colours_ ? colour_values == 3 || colour_values == 4 : colour_values == 0);
      if (!valid_count) {
        fail_here("vertex " + std::to_string(v) + " has " + std::to_string(tokens_.size()) +
                  " values; " + keyword_ + " vertices are '" + layout + "'");
      }
      mesh.positions.emplace_back(number<double>(tokens_[0]), number<double>(tokens_[1]),
                                  number<double>(tokens_[2]));
      if (normals_) {
        mesh.normals.emplace_back(number<double>(tokens_[3]), number<double>(tokens_[4]),
                                  number<double>(tokens_[5]));
      }
      if (colours_) read_colour(vertex_colours_, colour_start, colour_values, 1);
    }
  }

  void read_faces() {
    FaceBuilder faces(result_, name_);
    result_.mesh.triangles.reserve(face_count_);
    face_colours_.components.reserve(face_count_);
    std::vector<long long> polygon;
    for (long long f = 0; f < face_count_; ++f) {
      if (!next_line()) {
        fail(name_, "file ends after " + std::to_string(f) + " of the " +
                        std::to_string(face_count_) + " faces the header declares");
      }
      const std::string face = "face " + std::to_string(f);
      const long long corners = number<long long>(tokens_[0]);
      if (corners < 3) {
        fail_here(face + " has " + std::to_string(corners) + " vertices; at least 3 are needed");
      }
      const size_t listed = tokens_.size() - 1;
      if (static_cast<unsigned long long>(corners) > listed) {
        fail_here(face + " declares " + std::to_string(corners) + " vertices but lists " +
                  std::to_string(listed) + " values");
      }
      polygon.clear();
      for (long long k = 1; k <= corners; ++k) polygon.push_back(number<long long>(tokens_[k]));
      const size_t colour_values = listed - static_cast<size_t>(corners);
      if (colour_values != 0 && colour_values != 1 && colour_values != 3 && colour_values != 4) {
        fail_here(face + " has " + std::to_string(colour_values) +
                  " values after its vertex indices; expected none, a colour-map index or "
                  "'r g b [a]'");
      }
      const int triangles = faces.add(polygon, f, reader_.line_number());
      if (colour_values >= 3) {
        read_colour(face_colours_, 1 + static_cast<size_t>(corners), colour_values, triangles);
      } else {
        if (colour_values == 1) {
          number<long long>(tokens_.back());
          ++face_colour_map_indices_;
        }
        face_colours_.components.insert(face_colours_.components.end(), triangles,
                                        std::array<float, 4>{});
      }
    }
    faces.finish();
    if (next_line()) {
      fail_here("unexpected data after the " + std::to_string(face_count_) +
                " faces the header declares");
    }
  }

  // Appends tokens_[first, first + count) (r g b [a]) to `column` `copies` times.
  void read_colour(ColourColumn& column, size_t first, size_t count, int copies) {
    std::array<float, 4> components{};
    for (size_t c = 0; c < count; ++c) {
      const std::string_view token = tokens_[first + c];
      const float value = number<float>(token);
      if (value < 0 || value > 255) {
        fail_here("colour component " + quote(token) + " is outside [0, 255]");
      }
      components[c] = value;
      column.integer_tokens = column.integer_tokens && is_integer_token(token);
      column.whole_numbers = column.whole_numbers && value == std::floor(value);
      column.max_component = std::max(column.max_component, value);
    }
    ++column.with_rgb;
    if (count == 4) ++column.with_alpha;
    column.components.insert(column.components.end(), copies, components);
  }

  void warn(const std::string& what) { result_.warnings.push_back(name_ + ": " + what); }

  void warn_if_ambiguous(const ColourColumn& column, const std::string& element) {
    if (column.integer_tokens && column.max_component == 1) {
      warn(element + " colours are whole numbers no greater than 1 and were read as 8-bit " +
           "values; floats in [0, 1] need a decimal point (1.0)");
    }
  }

  void store_colours() {
    Mesh& mesh = result_.mesh;
    if (colours_) {
      mesh.storage.color = vertex_colours_.type();
      mesh.colors.reserve(vertex_count_);
      for (size_t v = 0; v < vertex_colours_.components.size(); ++v) {
        mesh.colors.emplace_back(vertex_colours_.normalised(v, 0), vertex_colours_.normalised(v, 1),
                                 vertex_colours_.normalised(v, 2));
      }
      if (vertex_count_ > 0 && vertex_colours_.with_alpha == vertex_count_) {
        mesh.vertex_properties.push_back(vertex_colours_.property(3));
      } else if (vertex_colours_.with_alpha > 0) {
        warn("vertex alpha dropped: only " + std::to_string(vertex_colours_.with_alpha) + " of " +
             std::to_string(vertex_count_) + " vertices have one");
      }
      warn_if_ambiguous(vertex_colours_, "vertex");
    }
    if (face_count_ > 0 && face_colours_.with_rgb == face_count_) {
      const bool alpha = face_colours_.with_alpha == face_count_;
      for (int c = 0; c < (alpha ? 4 : 3); ++c) {
        mesh.face_properties.push_back(face_colours_.property(c));
      }
      if (!alpha && face_colours_.with_alpha > 0) {
        warn("face alpha dropped: only " + std::to_string(face_colours_.with_alpha) + " of " +
             std::to_string(face_count_) + " faces have one");
      }
      warn_if_ambiguous(face_colours_, "face");
    } else if (face_colours_.with_rgb > 0) {
      warn("face colours dropped: only " + std::to_string(face_colours_.with_rgb) + " of " +
           std::to_string(face_count_) + " faces have one");
    }
    if (face_colour_map_indices_ > 0) {
      warn(std::to_string(face_colour_map_indices_) +
           " face colour-map indices dropped (colour maps are not supported)");
    }
  }

  std::string_view bytes_;
  TokenReader reader_;
  const std::string& name_;
  ReadResult result_;
  std::vector<std::string_view> tokens_;
  std::string keyword_ = "OFF";
  bool colours_ = false;
  bool normals_ = false;
  long long vertex_count_ = 0;
  long long face_count_ = 0;
  ColourColumn vertex_colours_;
  ColourColumn face_colours_;
  long long face_colour_map_indices_ = 0;
};

// A property that holds a colour component: 8-bit or floating point, as PLY's reader keeps them.
const ExtraProperty* find_colour_property(const std::vector<ExtraProperty>& properties,
                                          const char* name) {
  for (const ExtraProperty& property : properties) {
    if (property.name == name &&
        (property.type == ScalarType::uint8 || property.type == ScalarType::float32 ||
         property.type == ScalarType::float64)) {
      return &property;
    }
  }
  return nullptr;
}

// The type a colour property is written in when its element's colours are written as floats.
ScalarType float_type(const ExtraProperty& property) {
  return property.type == ScalarType::float64 ? ScalarType::float64 : ScalarType::float32;
}

double normalised_value(const ExtraProperty& property, size_t element) {
  const double value = property.values[element];
  return property.type == ScalarType::uint8 ? value / 255.0 : value;
}

// Appends a colour component in [0, 1] as an 8-bit integer (type uint8) or as a float that the
// colour rule reads back as one.
void append_colour(std::string& out, double normalised, ScalarType type) {
  out += ' ';
  if (type == ScalarType::uint8) {
    append_number(out, std::clamp(std::round(normalised * 255.0), 0.0, 255.0), type);
    return;
  }
  const size_t start = out.size();
  append_number(out, normalised, type);
  if (out.find_first_not_of("-0123456789", start) == std::string::npos) out += ".0";
}

}  // namespace

ReadResult parse_off(std::string_view bytes, const std::string& name) {
  return OffParser(bytes, name).parse();
}

void serialize_off(const Mesh& mesh, ByteSink& sink) {
  const ExtraProperty* vertex_alpha =
      mesh.has_colors() ? find_colour_property(mesh.vertex_properties, "alpha") : nullptr;
  const bool eight_bit_vertices = mesh.storage.color == ScalarType::uint8 &&
                                  (!vertex_alpha || vertex_alpha->type == ScalarType::uint8);
  std::array<const ExtraProperty*, 4> face_colour{};
  for (size_t c = 0; c < face_colour.size(); ++c) {
    face_colour[c] = find_colour_property(mesh.face_properties, kColourNames[c]);
  }
  const bool face_colours = face_colour[0] && face_colour[1] && face_colour[2];
  const bool eight_bit_faces =
      std::all_of(face_colour.begin(), face_colour.end(), [](const ExtraProperty* property) {
        return !property || property->type == ScalarType::uint8;
      });

  std::string& out = sink.bytes();
  if (mesh.has_colors()) out += 'C';
  if (mesh.has_normals()) out += 'N';
  out += "OFF\n" + std::to_string(mesh.vertex_count()) + ' ' + std::to_string(mesh.face_count()) +
         " 0\n";
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    append_numbers(out, mesh.positions[v], mesh.storage.position);
    if (mesh.has_normals()) {
      out += ' ';
      append_numbers(out, mesh.normals[v], mesh.storage.normal);
    }
    if (mesh.has_colors()) {
      const ScalarType type = eight_bit_vertices ? ScalarType::uint8 : ScalarType::float32;
      for (int c = 0; c < 3; ++c) append_colour(out, mesh.colors[v][c], type);
      if (vertex_alpha) {
        append_colour(out, normalised_value(*vertex_alpha, v),
                      eight_bit_vertices ? ScalarType::uint8 : float_type(*vertex_alpha));
      }
    }
    out += '\n';
    sink.end_record();
  }
  for (int f = 0; f < mesh.face_count(); ++f) {
    const Triangle& t = mesh.triangles[f];
    out += "3 " + std::to_string(t[0]) + ' ' + std::to_string(t[1]) + ' ' + std::to_string(t[2]);
    if (face_colours) {
      for (const ExtraProperty* property : face_colour) {
        if (property) {
          append_colour(out, normalised_value(*property, f),
                        eight_bit_faces ? ScalarType::uint8 : float_type(*property));
        }
      }
    }
    out += '\n';
    sink.end_record();
  }
}

}  // namespace rangefill::detail
