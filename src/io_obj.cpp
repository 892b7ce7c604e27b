// Wavefront OBJ through tinyobjloader: vertices (with "v x y z r g b" colours), normals and faces;
// groups, objects and material names are read past, texture coordinates, lines and points dropped.
//
// tinyobjloader 2.0.0rc10 cannot be trusted with the numbers: its parser is not correctly rounded
// (0.7 reads as 0.70000000000000007, 1.7976931348623157e308 as inf), it reads missing or malformed
// numbers ("nan", "1,5", the z of "v 1 2") as 0 without a word, reads face indices with atoi
// (4294967297 wraps to 1), returns out-of-range indices with only a warning, and counts a face's
// corners in an unsigned char (a 256-gon has 0). So a first pass here reads the v and vn lines
// exactly and checks every f line; tinyobjloader's vertex, normal and face counts are checked
// against it, and its faces (relative indices resolved) are range-checked before use.
//
// Colours are floats in [0, 1]; if any component exceeds 1, all are taken as 8-bit (0-255). Their
// type is uint8 when every colour is exactly c / 255 for an integer c, float32 otherwise.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <istream>
#include <streambuf>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "io_formats.h"

namespace rangefill::detail {

namespace {

// The library is built with TINYOBJLOADER_USE_DOUBLE; a header without it would misread its arrays.
static_assert(std::is_same_v<tinyobj::real_t, double>, "link tinyobjloader::tinyobjloader_double");

// What the v, vn and f lines hold, read exactly.
struct ObjLines {
  std::vector<Vec3> positions;
  std::vector<Rgb> colors;  // as written, of the v lines that have one
  long long coloured_vertices = 0;
  float max_colour_component = 0;
  std::vector<Vec3> normals;
  std::vector<int> face_sizes;
  std::vector<long long> face_lines;
  long long texture_coordinates = 0;
  long long polylines_and_points = 0;
};

// Checks an f line's vertex reference: v, v/vt, v//vn or v/vt/vn, non-zero int indices.
void check_vertex_reference(std::string_view token, const std::string& name, long long line) {
  bool valid = true;
  size_t start = 0;
  for (int part = 0;; ++part) {  // 0: v, 1: vt, 2: vn
    const size_t slash = token.find('/', start);
    const std::string_view text =
        token.substr(start, slash == token.npos ? token.npos : slash - start);
    const bool empty_vt = part == 1 && text.empty() && slash != token.npos;  // v//vn
    int index = 0;
    valid = valid && part < 3 && (empty_vt || (parse_number(text, index) && index != 0));
    if (slash == token.npos) break;
    start = slash + 1;
  }
  if (!valid) {
    fail_at(name, line,
            quote(token) + " is not a vertex reference (v, v/vt, v//vn or v/vt/vn, with non-zero " +
                "32-bit indices)");
  }
}

ObjLines read_lines(std::string_view bytes, const std::string& name) {
  ObjLines lines;
  TokenReader reader(bytes);
  std::vector<std::string_view> values;
  while (reader.next_line()) {
    const std::string_view keyword = reader.token();
    if (keyword == "vt") ++lines.texture_coordinates;
    if (keyword == "l" || keyword == "p") ++lines.polylines_and_points;
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
        ++lines.coloured_vertices;
        lines.max_colour_component = std::max(lines.max_colour_component, colour.maxCoeff());
        lines.colors.push_back(colour);
      }
    } else if (keyword == "vn") {
      if (values.size() != 3) {
        fail_at(name, line,
                "normal has " + std::to_string(values.size()) + " values; expected 'vn x y z'");
      }
      lines.normals.emplace_back(number(0), number(1), number(2));
    } else {
      if (values.size() < 3) {
        fail_at(name, line,
                "face has " + std::to_string(values.size()) + " vertices; at least 3 are needed");
      }
      for (std::string_view token : values) check_vertex_reference(token, name, line);
      lines.face_sizes.push_back(static_cast<int>(values.size()));
      lines.face_lines.push_back(line);
    }
  }
  return lines;
}

// A read-only stream over bytes in memory, for tinyobjloader, without copying them.
class MemoryBuffer : public std::streambuf {
 public:
  explicit MemoryBuffer(std::string_view bytes) {
    char* begin = const_cast<char*>(bytes.data());  // never written: no put area, no putback
    setg(begin, begin, begin + bytes.size());
  }
};

// tinyobjloader's messages, one per line; a message repeated is given once with its count.
std::vector<std::string> message_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::vector<long long> repeats;
  std::unordered_map<std::string, size_t> index;
  size_t start = 0;
  while (start < text.size()) {
    const size_t end = std::min(text.find('\n', start), text.size());
    std::string line = text.substr(start, end - start);
    start = end + 1;
    line.erase(0, line.find_first_not_of(" \t\r"));
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (line.empty()) continue;
    const auto [entry, inserted] = index.try_emplace(line, lines.size());
    if (inserted) {
      lines.push_back(line);
      repeats.push_back(1);
    } else {
      ++repeats[entry->second];
    }
  }
  for (size_t i = 0; i < lines.size(); ++i) {
    if (repeats[i] > 1) lines[i] += " (" + std::to_string(repeats[i]) + " times)";
  }
  return lines;
}

bool is_eight_bit(float normalised) {
  return normalised == static_cast<float>(std::round(normalised * 255.0) * (1.0 / 255.0));
}

}  // namespace

ReadResult parse_obj(std::string_view bytes, const std::string& name) {
  if (bytes.empty()) fail(name, "file is empty");
  ObjLines lines = read_lines(bytes, name);

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warnings, errors;
  MemoryBuffer buffer(bytes);
  std::istream stream(&buffer);
  const bool loaded = tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &stream,
                                       /*readMatFn=*/nullptr, /*triangulate=*/false,
                                       /*default_vcols_fallback=*/false);
  if (!loaded || !errors.empty()) {
    std::string what = "tinyobjloader could not read the file";
    const std::vector<std::string> messages = message_lines(errors);
    for (size_t i = 0; i < messages.size(); ++i) what += (i == 0 ? ": " : "; ") + messages[i];
    fail(name, what);
  }

  const size_t vertex_count = lines.positions.size();
  const size_t normal_count = lines.normals.size();
  size_t face_count = 0;
  for (const tinyobj::shape_t& shape : shapes) face_count += shape.mesh.num_face_vertices.size();
  if (attrib.vertices.size() != 3 * vertex_count || attrib.normals.size() != 3 * normal_count ||
      face_count != lines.face_sizes.size()) {
    fail(name, "tinyobjloader read " + std::to_string(attrib.vertices.size() / 3) + " vertices, " +
                   std::to_string(attrib.normals.size() / 3) + " normals and " +
                   std::to_string(face_count) + " faces where the file has " +
                   std::to_string(vertex_count) + " v, " + std::to_string(normal_count) +
                   " vn and " + std::to_string(lines.face_sizes.size()) +
                   " f lines (unusual line breaks or white space?)");
  }

  ReadResult result;
  Mesh& mesh = result.mesh;
  mesh.positions = std::move(lines.positions);
  mesh.vertex_hole.assign(vertex_count, kOriginal);
  mesh.storage.position = ScalarType::float64;
  mesh.storage.normal = ScalarType::float64;
  for (const std::string& line : message_lines(warnings)) {
    result.warnings.push_back(name + ": " + line);
  }

  // Faces, and the normal index each vertex is paired with (-1: none, -2: in no face yet).
  FaceBuilder faces(result, name);
  mesh.triangles.reserve(face_count);
  std::vector<int> vertex_normal(vertex_count, -2);
  std::string normals_unusable;  // why, when they are
  std::vector<long long> polygon;
  size_t face = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    size_t corner = 0;
    for (const unsigned char declared_size : shape.mesh.num_face_vertices) {
      const int size = lines.face_sizes[face];
      const long long line = lines.face_lines[face];
      if (declared_size != static_cast<unsigned char>(size) ||
          corner + size > shape.mesh.indices.size()) {
        fail_at(name, line, "tinyobjloader read this face with a different number of corners");
      }
      polygon.clear();
      for (int k = 0; k < size; ++k) {
        const tinyobj::index_t& index = shape.mesh.indices[corner + k];
        // A relative index reaching before the first vertex resolves to a negative value.
        if (index.vertex_index < 0) {
          fail_at(name, line, "face refers to a vertex before the first one (relative index)");
        }
        if (static_cast<size_t>(index.vertex_index) >= vertex_count) {
          fail_at(name, line,
                  "face refers to vertex " + std::to_string(index.vertex_index + 1LL) +
                      ", outside the file's " + std::to_string(vertex_count) + " vertices");
        }
        if (index.normal_index < -1 || index.normal_index >= static_cast<int>(normal_count)) {
          fail_at(name, line,
                  "face refers to normal " + std::to_string(index.normal_index + 1LL) +
                      ", outside the file's " + std::to_string(normal_count) + " normals");
        }
        polygon.push_back(index.vertex_index);
        int& paired = vertex_normal[index.vertex_index];
        if (!normals_unusable.empty()) continue;
        if (index.normal_index == -1) {
          normals_unusable = "line " + std::to_string(line) + " has a face corner without one";
        } else if (paired >= 0 && paired != index.normal_index) {
          normals_unusable = "vertex " + std::to_string(index.vertex_index + 1) +
                             " is paired with normals " + std::to_string(paired + 1) + " and " +
                             std::to_string(index.normal_index + 1);
        }
        paired = index.normal_index;
      }
      faces.add(polygon, static_cast<long long>(face), line);
      corner += size;
      ++face;
    }
  }
  faces.finish();

  if (normal_count > 0) {
    if (face_count == 0) normals_unusable = "no face refers to them";
    if (normals_unusable.empty()) {
      // Vertices in no face get a zero normal, as generated ones do.
      mesh.normals.assign(vertex_count, Vec3::Zero());
      for (size_t v = 0; v < vertex_count; ++v) {
        if (vertex_normal[v] >= 0) mesh.normals[v] = lines.normals[vertex_normal[v]];
      }
    } else {
      result.warnings.push_back(
          name + ": normals dropped (rangefill keeps one per vertex): " + normals_unusable);
    }
  }

  if (vertex_count > 0 && lines.coloured_vertices == static_cast<long long>(vertex_count)) {
    const bool eight_bit = lines.max_colour_component > 1;
    mesh.colors = std::move(lines.colors);
    bool all_eight_bit = true;
    for (Rgb& colour : mesh.colors) {
      if (eight_bit) colour = (colour.cast<double>() * (1.0 / 255.0)).cast<float>();
      all_eight_bit = all_eight_bit && is_eight_bit(colour[0]) && is_eight_bit(colour[1]) &&
                      is_eight_bit(colour[2]);
    }
    mesh.storage.color = all_eight_bit ? ScalarType::uint8 : ScalarType::float32;
  } else if (lines.coloured_vertices > 0) {
    result.warnings.push_back(name + ": vertex colours dropped: only " +
                              std::to_string(lines.coloured_vertices) + " of " +
                              std::to_string(vertex_count) + " vertices have one");
  }
  if (lines.texture_coordinates > 0) {
    result.warnings.push_back(name + ": " + std::to_string(lines.texture_coordinates) +
                              " texture coordinates (vt) dropped");
  }
  if (lines.polylines_and_points > 0) {
    result.warnings.push_back(name + ": " + std::to_string(lines.polylines_and_points) +
                              " polylines and point elements (l, p) dropped");
  }
  return result;
}

std::string serialize_obj(const Mesh& mesh) {
  std::string out = "# written by rangefill\n";
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    out += "v ";
    append_numbers(out, mesh.positions[v], mesh.storage.position);
    if (mesh.has_colors()) {
      out += ' ';
      append_numbers(out, mesh.colors[v].cast<double>(), ScalarType::float32);
    }
    out += '\n';
  }
  for (const Vec3& normal : mesh.normals) {
    out += "vn ";
    append_numbers(out, normal, mesh.storage.normal);
    out += '\n';
  }
  for (const Triangle& triangle : mesh.triangles) {
    out += 'f';
    for (int v : triangle) {
      const std::string index = std::to_string(v + 1);
      out += ' ' + index;
      if (mesh.has_normals()) out += "//" + index;
    }
    out += '\n';
  }
  return out;
}

}  // namespace rangefill::detail
