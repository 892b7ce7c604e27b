// STL, binary (little endian) and ASCII. Our own parser: STL stores every facet's corners apart,
// and the maintained readers (VTK's, PCL's) merge points within a tolerance and reorder them. Here
// corners are welded only when their float coordinates are bit-identical, numbering vertices in
// order of first occurrence. Facet normals are not per-vertex data and are ignored.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include "io/formats.h"

namespace rangefill::detail {

namespace {

constexpr size_t kHeaderSize = 80;
constexpr size_t kPrefixSize = kHeaderSize + 4;  // header, facet count
constexpr size_t kFacetSize = 50;  // normal and 3 corners (float32), attribute (uint16)

using Corner = std::array<float, 3>;

std::uint32_t float_bits(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

std::uint32_t read_uint32_le(const char* bytes) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes);
  return b[0] | b[1] << 8 | b[2] << 16 | static_cast<std::uint32_t>(b[3]) << 24;
}

float read_float_le(const char* bytes) {
  const std::uint32_t bits = read_uint32_le(bytes);
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

void append_uint32_le(std::string& out, std::uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) out += static_cast<char>((value >> shift) & 0xff);
}

void append_float_le(std::string& out, float value) {
  append_uint32_le(out, float_bits(value));
}

// Whether `text` equals the lower-case `keyword`, ignoring case.
bool iequals(std::string_view text, std::string_view keyword) {
  if (text.size() != keyword.size()) return false;
  for (size_t i = 0; i < text.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(text[i])) != keyword[i]) return false;
  }
  return true;
}

// Welds corners with bit-identical coordinates into vertices numbered in order of first occurrence;
// drops (and counts) facets whose corners are not three distinct points.
class Welder {
 public:
  explicit Welder(Mesh& mesh) : mesh_(mesh) {}

  void add_facet(const std::array<Corner, 3>& corners) {
    std::array<Key, 3> keys;
    for (int c = 0; c < 3; ++c) {
      keys[c] = {float_bits(corners[c][0]), float_bits(corners[c][1]), float_bits(corners[c][2])};
    }
    if (keys[0] == keys[1] || keys[1] == keys[2] || keys[2] == keys[0]) {
      ++degenerate_facets_;
      return;
    }
    Triangle triangle;
    for (int c = 0; c < 3; ++c) {
      const auto [entry, inserted] = vertices_.try_emplace(keys[c], mesh_.vertex_count());
      if (inserted) {
        mesh_.positions.emplace_back(corners[c][0], corners[c][1], corners[c][2]);
      }
      triangle[c] = entry->second;
    }
    mesh_.triangles.push_back(triangle);
  }

  long long degenerate_facets() const { return degenerate_facets_; }

 private:
  using Key = std::array<std::uint32_t, 3>;
  struct KeyHash {
    size_t operator()(const Key& key) const {
      return std::hash<std::uint64_t>()((std::uint64_t{key[0]} << 32 | key[1]) ^
                                        (std::uint64_t{key[2]} * 0x9e3779b97f4a7c15ULL));
    }
  };

  Mesh& mesh_;
  std::unordered_map<Key, int, KeyHash> vertices_;
  long long degenerate_facets_ = 0;
};

void read_binary(std::string_view bytes, size_t facet_count, Welder& welder, ReadResult& result,
                 const std::string& name) {
  result.mesh.triangles.reserve(facet_count);
  long long with_attributes = 0;
  for (size_t f = 0; f < facet_count; ++f) {
    const char* facet = bytes.data() + kPrefixSize + f * kFacetSize;
    std::array<Corner, 3> corners;
    for (int c = 0; c < 3; ++c) {
      for (int axis = 0; axis < 3; ++axis) {
        corners[c][axis] = read_float_le(facet + 12 * (c + 1) + 4 * axis);
      }
    }
    if (facet[48] != 0 || facet[49] != 0) ++with_attributes;
    welder.add_facet(corners);
  }
  if (with_attributes > 0) {
    result.warnings.push_back(name + ": attribute bytes (often a colour) of " +
                              std::to_string(with_attributes) + " facets dropped");
  }
}

// ASCII STL: "solid name", facets ("facet normal nx ny nz", "outer loop", three "vertex x y z",
// "endloop", "endfacet"), "endsolid name"; several solids in a row; keywords in any case.
class AsciiReader {
 public:
  AsciiReader(std::string_view bytes, const std::string& name, Welder& welder, ReadResult& result)
      : reader_(bytes), name_(name), welder_(welder), result_(result) {}

  void read() {
    for (std::string_view token = next(); !token.empty(); token = next()) {
      if (!iequals(token, "solid")) fail_here("expected 'solid', found " + quote(token));
      skip_rest_of_line();  // the solid's name
      if (!read_facets()) {
        result_.warnings.push_back(name_ + ": file ends without 'endsolid' (truncated?)");
        return;
      }
    }
  }

 private:
  // Reads facets up to and including "endsolid"; false if the file ends first.
  bool read_facets() {
    for (;;) {
      const std::string_view token = next();
      if (token.empty()) return false;
      if (iequals(token, "endsolid")) {
        skip_rest_of_line();
        return true;
      }
      if (!iequals(token, "facet"))
        fail_here("expected 'facet' or 'endsolid', found " + quote(token));
      expect("normal");
      for (int axis = 0; axis < 3; ++axis) {
        double ignored;
        const std::string_view component = expect_token("a normal component");
        if (!parse_number(component, ignored)) {
          fail_here(quote(component) + " is not a valid number");
        }
      }
      expect("outer");
      expect("loop");
      std::array<Corner, 3> corners;
      for (Corner& corner : corners) {
        expect("vertex");
        for (float& coordinate : corner) {
          coordinate =
              parse_number_at<float>(expect_token("a coordinate"), name_, reader_.line_number());
        }
      }
      expect("endloop");
      expect("endfacet");
      welder_.add_facet(corners);
    }
  }

  // The next token, across lines; empty at the end of the file.
  std::string_view next() {
    for (;;) {
      const std::string_view token = reader_.token();
      if (!token.empty()) return token;
      if (!reader_.next_line('\0')) return {};  // STL has no comments
    }
  }

  std::string_view expect_token(const std::string& what) {
    const std::string_view token = next();
    if (token.empty()) fail(name_, "file ends where " + what + " was expected");
    return token;
  }

  void expect(const char* keyword) {
    const std::string_view token = expect_token(std::string("'") + keyword + "'");
    if (!iequals(token, keyword)) {
      fail_here(std::string("expected '") + keyword + "', found " + quote(token));
    }
  }

  void skip_rest_of_line() {
    while (!reader_.token().empty()) {
    }
  }

  [[noreturn]] void fail_here(const std::string& what) const {
    fail_at(name_, reader_.line_number(), what);
  }

  TokenReader reader_;
  const std::string& name_;
  Welder& welder_;
  ReadResult& result_;
};

}  // namespace

ReadResult parse_stl(std::string_view bytes, const std::string& name) {
  if (bytes.empty()) fail(name, "file is empty");
  ReadResult result;
  Welder welder(result.mesh);
  const size_t text_start = std::min(bytes.find_first_not_of(" \t\r\n"), bytes.size());
  const bool starts_with_solid = iequals(bytes.substr(text_start, 5), "solid");
  const size_t declared_facets =
      bytes.size() >= kPrefixSize ? read_uint32_le(bytes.data() + kHeaderSize) : 0;
  if (bytes.size() >= kPrefixSize && bytes.size() == kPrefixSize + kFacetSize * declared_facets) {
    read_binary(bytes, declared_facets, welder, result, name);
  } else if (starts_with_solid && bytes.find('\0') == std::string_view::npos) {
    AsciiReader(bytes, name, welder, result).read();
  } else if (bytes.size() < kPrefixSize) {
    fail(name, "not ASCII STL (no 'solid' at the start) and, at " + std::to_string(bytes.size()) +
                   " bytes, too short for binary STL");
  } else {
    fail(name, "binary STL header declares " + std::to_string(declared_facets) + " facets (" +
                   std::to_string(kPrefixSize + kFacetSize * declared_facets) +
                   " bytes) but the file has " + std::to_string(bytes.size()) +
                   " bytes: truncated or not STL");
  }
  if (welder.degenerate_facets() > 0) {
    result.warnings.push_back(name + ": " + std::to_string(welder.degenerate_facets()) +
                              " degenerate facets (corners not three distinct points) dropped");
  }
  result.mesh.storage.position = ScalarType::float32;
  result.mesh.vertex_hole.assign(result.mesh.positions.size(), kOriginal);
  result.mesh.face_hole.assign(result.mesh.triangles.size(), kOriginal);
  return result;
}

void serialize_stl(const Mesh& mesh, const WriteOptions& options, ByteSink& sink) {
  std::vector<Vec3> normals(mesh.face_count(), Vec3::Zero());
  for (int f = 0; f < mesh.face_count(); ++f) {
    const Vec3 cross = triangle_cross(mesh, f);
    const double length = cross.norm();
    if (length > 0 && std::isfinite(length)) normals[f] = cross / length;
  }
  std::string& out = sink.bytes();
  if (options.encoding == Encoding::ascii) {
    out += "solid rangefill\n";
    for (int f = 0; f < mesh.face_count(); ++f) {
      out += "facet normal ";
      append_numbers(out, normals[f], ScalarType::float32);
      out += "\n  outer loop\n";
      for (int v : mesh.triangles[f]) {
        out += "    vertex ";
        append_numbers(out, mesh.positions[v], ScalarType::float32);
        out += '\n';
      }
      out += "  endloop\nendfacet\n";
      sink.end_record();
    }
    out += "endsolid rangefill\n";
    return;
  }
  out = "rangefill";  // must not start with "solid", which readers take for ASCII
  out.resize(kHeaderSize, ' ');
  sink.expect(kPrefixSize - kHeaderSize + kFacetSize * mesh.triangles.size());
  append_uint32_le(out, static_cast<std::uint32_t>(mesh.face_count()));
  for (int f = 0; f < mesh.face_count(); ++f) {
    for (int axis = 0; axis < 3; ++axis) append_float_le(out, static_cast<float>(normals[f][axis]));
    for (int v : mesh.triangles[f]) {
      for (int axis = 0; axis < 3; ++axis) {
        append_float_le(out, static_cast<float>(mesh.positions[v][axis]));
      }
    }
    out.append(2, '\0');  // attribute byte count
    sink.end_record();
  }
}

}  // namespace rangefill::detail
