// Wavefront OBJ, read in one pass: vertices (with "v x y z r g b" colours), normals and faces;
// groups and objects are read past, materials, texture coordinates, lines and points dropped.
//
// Our own parser rather than tinyobjloader (Debian's 2.0.0rc10), which does not round numbers
// correctly (0.7 reads as 0.70000000000000007, 1.7976931348623157e308 as inf), reads missing or
// malformed ones ("nan", "1,5", the z of "v 1 2") as 0 without a word, reads face indices with
// atoi (4294967297 wraps to 1) and counts a face's corners in one byte (a 256-gon has 0).
//
// Face indices are 1-based; a negative one counts back from the last vertex (normal) read so far.
// Positive ones may refer to vertices defined further on and are range-checked after the pass.
// Colours are floats in [0, 1]; if any component exceeds 1, all are taken as 8-bit (0-255). Their
// type is uint8 when every colour is exactly c / 255 for an integer c, float32 otherwise.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "io/formats.h"

namespace rangefill::detail {

namespace {

// A face corner, resolved to 0-based indices (normal -1: none); not yet range-checked.
struct Corner {
  int vertex;
  int normal;
};

// A face: its corners are those from `first_corner` to the next face's.
struct Face {
  size_t first_corner;
  long long line;
};

// What the lines hold.
struct ObjLines {
  std::vector<Vec3> positions;
  std::vector<Rgb> colors;  // as written, of the v lines that have one
  float max_colour_component = 0;
  std::vector<Vec3> normals;
  std::vector<Corner> corners;
  std::vector<Face> faces;
  long long texture_coordinates = 0;
  long long polylines_and_points = 0;
  long long material_uses = 0;
};

// Reads an f line's vertex reference: v, v/vt, v//vn or v/vt/vn, non-zero 32-bit indices as
// written (normal 0: none). The vt index is checked, not kept.
bool parse_reference(std::string_view token, int& vertex, int& normal) {
  auto index = [](std::string_view text, int& value) {
    return parse_number(text, value) && value != 0;
  };
  const size_t first = token.find('/');
  const size_t second = first == token.npos ? token.npos : token.find('/', first + 1);
  normal = 0;
  if (!index(token.substr(0, first), vertex)) return false;
  if (first == token.npos) return true;
  int texture = 0;
  const std::string_view vt =
      token.substr(first + 1, second == token.npos ? token.npos : second - first - 1);
  if (second == token.npos) return index(vt, texture);
  return (vt.empty() || index(vt, texture)) && index(token.substr(second + 1), normal);
}

ObjLines read_lines(std::string_view bytes, const std::string& name) {
  constexpr size_t kMaxCount = std::numeric_limits<int>::max();
  ObjLines lines;
  TokenReader reader(bytes);
  std::vector<std::string_view> values;
  while (reader.next_line()) {
    const std::string_view keyword = reader.token();
    if (keyword == "vt") ++lines.texture_coordinates;
    if (keyword == "l" || keyword == "p") ++lines.polylines_and_points;
    if (keyword == "usemtl") ++lines.material_uses;
    if (keyword != "v" && keyword != "vn" && keyword != "f") continue;
    const long long line = reader.line_number();
    values.clear();
    for (std::string_view token = reader.token(); !token.empty(); token = reader.token()) {
      values.push_back(token);
    }
    auto number = [&](size_t i) { return parse_number_at<double>(values[i], name, line); };
    if (keyword == "v") {
      if (values.size() == 4 && number(3) == 1) values.pop_back();  // the weight w, 1 by default
      if (values.size() != 3 && values.size() != 6) {
        fail_at(name, line,
                "vertex has " + std::to_string(values.size()) + " values; expected 'v x y z' or " +
                    "'v x y z r g b'");
      }
      if (lines.positions.size() == kMaxCount) fail_at(name, line, "too many vertices");
      lines.positions.emplace_back(number(0), number(1), number(2));
      if (values.size() == 6) {
        Rgb colour;
        for (int c = 0; c < 3; ++c) {
          colour[c] = parse_number_at<float>(values[3 + c], name, line);
          if (colour[c] < 0 || colour[c] > 255) {
            fail_at(name, line,
                    "colour component " + quote(values[3 + c]) + " is outside [0, 255]");
          }
        }
        lines.max_colour_component = std::max(lines.max_colour_component, colour.maxCoeff());
        lines.colors.push_back(colour);
      }
    } else if (keyword == "vn") {
      if (values.size() != 3) {
        fail_at(name, line,
                "normal has " + std::to_string(values.size()) + " values; expected 'vn x y z'");
      }
      if (lines.normals.size() == kMaxCount) fail_at(name, line, "too many normals");
      lines.normals.emplace_back(number(0), number(1), number(2));
    } else {
      if (values.size() < 3) {
        fail_at(name, line,
                "face has " + std::to_string(values.size()) + " vertices; at least 3 are needed");
      }
      // 1-based, or relative to the `count` read so far; 0-based on return.
      auto resolve = [&](int index, size_t count, const std::string& element) {
        const long long resolved = index > 0 ? index - 1LL : static_cast<long long>(count) + index;
        if (resolved < 0) {
          fail_at(name, line,
                  "face refers to a " + element + " before the first one (relative index " +
                      std::to_string(index) + " with " + std::to_string(count) + " read so far)");
        }
        return static_cast<int>(resolved);
      };
      lines.faces.push_back({lines.corners.size(), line});
      for (std::string_view token : values) {
        int vertex = 0, normal = 0;
        if (!parse_reference(token, vertex, normal)) {
          fail_at(name, line,
                  quote(token) + " is not a vertex reference (v, v/vt, v//vn or v/vt/vn, with " +
                      "non-zero 32-bit indices)");
        }
        lines.corners.push_back(
            {resolve(vertex, lines.positions.size(), "vertex"),
             normal == 0 ? -1 : resolve(normal, lines.normals.size(), "normal")});
      }
    }
  }
  return lines;
}

bool is_eight_bit(float normalised) {
  return normalised == static_cast<float>(std::round(normalised * 255.0) * (1.0 / 255.0));
}

// The v lines' colours into the mesh when every vertex has one (8-bit when any component exceeds
// 1), else dropped with a warning.
void take_colours(ObjLines& lines, const std::string& name, ReadResult& result) {
  Mesh& mesh = result.mesh;
  const size_t vertex_count = mesh.positions.size();
  const size_t coloured_vertices = lines.colors.size();
  if (vertex_count > 0 && coloured_vertices == vertex_count) {
    const bool eight_bit = lines.max_colour_component > 1;
    mesh.colors = std::move(lines.colors);
    bool all_eight_bit = true;
    for (Rgb& colour : mesh.colors) {
      if (eight_bit) colour = (colour.cast<double>() * (1.0 / 255.0)).cast<float>();
      all_eight_bit = all_eight_bit && is_eight_bit(colour[0]) && is_eight_bit(colour[1]) &&
                      is_eight_bit(colour[2]);
    }
    mesh.storage.color = all_eight_bit ? ScalarType::uint8 : ScalarType::float32;
  } else if (coloured_vertices > 0) {
    result.warnings.push_back(name + ": vertex colours dropped: only " +
                              std::to_string(coloured_vertices) + " of " +
                              std::to_string(vertex_count) + " vertices have one");
  }
}

// The normals into the mesh, one per vertex as its face corners pair them (`vertex_normal`), unless
// `unusable` says why not (then dropped with a warning).
void take_normals(const ObjLines& lines, const std::vector<int>& vertex_normal,
                  std::string unusable, const std::string& name, ReadResult& result) {
  if (lines.normals.empty()) return;
  if (lines.faces.empty()) unusable = "no face refers to them";
  if (!unusable.empty()) {
    result.warnings.push_back(name +
                              ": normals dropped (rangefill keeps one per vertex): " + unusable);
    return;
  }
  // Vertices in no face get a zero normal, as generated ones do.
  Mesh& mesh = result.mesh;
  mesh.normals.assign(mesh.positions.size(), Vec3::Zero());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    if (vertex_normal[v] >= 0) mesh.normals[v] = lines.normals[vertex_normal[v]];
  }
}

}  // namespace

ReadResult parse_obj(std::string_view bytes, const std::string& name) {
  if (bytes.empty()) fail(name, "file is empty");
  ObjLines lines = read_lines(bytes, name);

  ReadResult result;
  Mesh& mesh = result.mesh;
  mesh.positions = std::move(lines.positions);
  const size_t vertex_count = mesh.positions.size();
  const size_t normal_count = lines.normals.size();
  mesh.vertex_hole.assign(vertex_count, kOriginal);
  mesh.storage.position = ScalarType::float64;
  mesh.storage.normal = ScalarType::float64;

  // Faces, and the normal index each vertex is paired with (-1: none, -2: in no face yet).
  FaceBuilder builder(result, name);
  mesh.triangles.reserve(lines.faces.size());
  std::vector<int> vertex_normal(normal_count > 0 ? vertex_count : 0, -2);
  std::string normals_unusable;  // why, when they are
  std::vector<long long> polygon;
  for (size_t f = 0; f < lines.faces.size(); ++f) {
    const long long line = lines.faces[f].line;
    const size_t end =
        f + 1 < lines.faces.size() ? lines.faces[f + 1].first_corner : lines.corners.size();
    polygon.clear();
    for (size_t c = lines.faces[f].first_corner; c < end; ++c) {
      const Corner corner = lines.corners[c];
      // Checked here rather than by FaceBuilder, so that messages count from 1 as the file does.
      if (static_cast<size_t>(corner.vertex) >= vertex_count) {
        fail_at(name, line,
                "face refers to vertex " + std::to_string(corner.vertex + 1LL) +
                    ", outside the file's " + std::to_string(vertex_count) + " vertices");
      }
      if (corner.normal >= 0 && static_cast<size_t>(corner.normal) >= normal_count) {
        fail_at(name, line,
                "face refers to normal " + std::to_string(corner.normal + 1LL) +
                    ", outside the file's " + std::to_string(normal_count) + " normals");
      }
      if (std::find(polygon.begin(), polygon.end(), corner.vertex) != polygon.end()) {
        fail_at(name, line, "face repeats vertex " + std::to_string(corner.vertex + 1LL));
      }
      polygon.push_back(corner.vertex);
      if (normal_count == 0 || !normals_unusable.empty()) continue;
      int& paired = vertex_normal[corner.vertex];
      if (corner.normal < 0) {
        normals_unusable = "line " + std::to_string(line) + " has a face corner without one";
      } else if (paired >= 0 && paired != corner.normal) {
        normals_unusable = "vertex " + std::to_string(corner.vertex + 1LL) +
                           " is paired with normals " + std::to_string(paired + 1LL) + " and " +
                           std::to_string(corner.normal + 1LL);
      }
      paired = corner.normal;
    }
    builder.add(polygon, static_cast<long long>(f) + 1, line);
  }
  builder.finish();

  take_normals(lines, vertex_normal, normals_unusable, name, result);
  take_colours(lines, name, result);
  if (lines.texture_coordinates > 0) {
    result.warnings.push_back(name + ": " + std::to_string(lines.texture_coordinates) +
                              " texture coordinates (vt) dropped");
  }
  if (lines.polylines_and_points > 0) {
    result.warnings.push_back(name + ": " + std::to_string(lines.polylines_and_points) +
                              " polylines and point elements (l, p) dropped");
  }
  if (lines.material_uses > 0) {
    result.warnings.push_back(name + ": " + std::to_string(lines.material_uses) +
                              " material assignments (usemtl) dropped");
  }
  return result;
}

void serialize_obj(const Mesh& mesh, ByteSink& sink) {
  std::string& out = sink.bytes();
  out += "# written by rangefill\n";
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    out += "v ";
    append_numbers(out, mesh.positions[v], mesh.storage.position);
    if (mesh.has_colors()) {
      out += ' ';
      append_numbers(out, mesh.colors[v].cast<double>(), ScalarType::float32);
    }
    out += '\n';
    sink.end_record();
  }
  for (const Vec3& normal : mesh.normals) {
    out += "vn ";
    append_numbers(out, normal, mesh.storage.normal);
    out += '\n';
    sink.end_record();
  }
  for (const Triangle& triangle : mesh.triangles) {
    out += 'f';
    for (int v : triangle) {
      const std::string index = std::to_string(v + 1);
      out += ' ' + index;
      if (mesh.has_normals()) out += "//" + index;
    }
    out += '\n';
    sink.end_record();
  }
}

}  // namespace rangefill::detail
