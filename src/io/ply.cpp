// PLY (Turk 1994): ASCII and binary either endianness, any scalar types, polygons, unknown
// properties carried through. Our own parser rather than PCL's: PCL's reader drops face properties
// (we need provenance back), allocates from the header's counts before reading, and prints to the
// console; there is no other maintained PLY library in Debian.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "io/formats.h"

namespace rangefill::detail {

namespace {

constexpr const char* kProvenanceProperty = "rangefill_hole";

enum class PlyEncoding { ascii, binary_little_endian, binary_big_endian };

struct PlyProperty {
  std::string name;
  ScalarType type = ScalarType::float32;  // the item type for lists
  bool is_list = false;
  ScalarType count_type = ScalarType::uint8;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::ascii;
  std::vector<PlyElement> elements;
  size_t data_offset = 0;
};

size_t type_size(ScalarType type) {
  switch (type) {
    case ScalarType::int8:
    case ScalarType::uint8:
      return 1;
    case ScalarType::int16:
    case ScalarType::uint16:
      return 2;
    case ScalarType::int32:
    case ScalarType::uint32:
    case ScalarType::float32:
      return 4;
    case ScalarType::float64:
      return 8;
  }
  return 0;
}

bool is_integer(ScalarType type) {
  return type != ScalarType::float32 && type != ScalarType::float64;
}

// The values a type holds (a floating-point type: its finite ones).
template <typename T>
std::pair<double, double> range_of() {
  return {static_cast<double>(std::numeric_limits<T>::lowest()),
          static_cast<double>(std::numeric_limits<T>::max())};
}

std::pair<double, double> value_range(ScalarType type) {
  switch (type) {
    case ScalarType::int8:
      return range_of<std::int8_t>();
    case ScalarType::uint8:
      return range_of<std::uint8_t>();
    case ScalarType::int16:
      return range_of<std::int16_t>();
    case ScalarType::uint16:
      return range_of<std::uint16_t>();
    case ScalarType::int32:
      return range_of<std::int32_t>();
    case ScalarType::uint32:
      return range_of<std::uint32_t>();
    case ScalarType::float32:
      return range_of<float>();
    case ScalarType::float64:
      return range_of<double>();
  }
  return {0, 0};
}

bool parse_type(std::string_view name, ScalarType& type) {
  static const std::pair<const char*, ScalarType> kNames[] = {
      {"char", ScalarType::int8},      {"int8", ScalarType::int8},
      {"uchar", ScalarType::uint8},    {"uint8", ScalarType::uint8},
      {"short", ScalarType::int16},    {"int16", ScalarType::int16},
      {"ushort", ScalarType::uint16},  {"uint16", ScalarType::uint16},
      {"int", ScalarType::int32},      {"int32", ScalarType::int32},
      {"uint", ScalarType::uint32},    {"uint32", ScalarType::uint32},
      {"float", ScalarType::float32},  {"float32", ScalarType::float32},
      {"double", ScalarType::float64}, {"float64", ScalarType::float64}};
  for (const auto& [text, value] : kNames) {
    if (name == text) {
      type = value;
      return true;
    }
  }
  return false;
}

const char* type_name(ScalarType type) {
  switch (type) {
    case ScalarType::int8:
      return "char";
    case ScalarType::uint8:
      return "uchar";
    case ScalarType::int16:
      return "short";
    case ScalarType::uint16:
      return "ushort";
    case ScalarType::int32:
      return "int";
    case ScalarType::uint32:
      return "uint";
    case ScalarType::float32:
      return "float";
    case ScalarType::float64:
      return "double";
  }
  return "";
}

PlyHeader parse_header(std::string_view bytes, const std::string& name) {
  // The header is ASCII up to "end_header"; binary data may follow, so look for it first.
  if (bytes.substr(0, 3) != "ply") fail(name, "not a PLY file (no 'ply' magic)");
  const size_t end = bytes.find("end_header");
  if (end == std::string_view::npos) fail(name, "PLY header has no end_header");
  TokenReader reader(bytes.substr(0, bytes.find('\n', end) == std::string_view::npos
                                         ? bytes.size()
                                         : bytes.find('\n', end) + 1));
  PlyHeader header;
  bool have_format = false;
  reader.next_line('\0');  // "ply"
  while (reader.next_line('\0')) {
    const std::string where = "PLY header line " + std::to_string(reader.line_number());
    const std::string_view keyword = reader.token();
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      header.data_offset = reader.offset();
      if (!have_format) fail(name, "PLY header has no format line");
      return header;
    }
    if (keyword == "format") {
      const std::string_view format = reader.token();
      if (format == "ascii") {
        header.encoding = PlyEncoding::ascii;
      } else if (format == "binary_little_endian") {
        header.encoding = PlyEncoding::binary_little_endian;
      } else if (format == "binary_big_endian") {
        header.encoding = PlyEncoding::binary_big_endian;
      } else {
        fail(name, where + ": unknown format '" + std::string(format) + "'");
      }
      have_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      element.name = std::string(reader.token());
      if (element.name.empty() || !parse_number(reader.token(), element.count) ||
          element.count < 0) {
        fail(name, where + ": malformed element line");
      }
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) fail(name, where + ": property before any element");
      PlyProperty property;
      std::string_view type = reader.token();
      if (type == "list") {
        property.is_list = true;
        if (!parse_type(reader.token(), property.count_type) || !is_integer(property.count_type)) {
          fail(name, where + ": bad list count type");
        }
        type = reader.token();
      }
      if (!parse_type(type, property.type)) {
        fail(name, where + ": unknown property type '" + std::string(type) + "'");
      }
      property.name = std::string(reader.token());
      if (property.name.empty()) fail(name, where + ": property without a name");
      for (const PlyProperty& other : header.elements.back().properties) {
        if (other.name == property.name) {
          fail(name, where + ": property '" + property.name + "' declared twice in element '" +
                         header.elements.back().name + "'");
        }
      }
      header.elements.back().properties.push_back(std::move(property));
    } else {
      fail(name, where + ": unexpected '" + std::string(keyword) + "'");
    }
  }
  fail(name, "PLY header has no end_header");
}

// Rejects headers whose counts cannot fit in the bytes that follow, before anything is allocated.
void check_counts_fit(const PlyHeader& header, size_t data_size, const std::string& name) {
  long double least_bytes = 0;
  for (const PlyElement& element : header.elements) {
    size_t record = 0;  // the smallest possible record: lists empty
    for (const PlyProperty& property : element.properties) {
      record += header.encoding == PlyEncoding::ascii
                    ? 2  // one digit and a separator
                    : type_size(property.is_list ? property.count_type : property.type);
    }
    if (record == 0 && element.count > 0) {
      fail(name, "PLY element '" + element.name + "' has no properties");
    }
    least_bytes += static_cast<long double>(record) * static_cast<long double>(element.count);
    if (least_bytes >
        static_cast<long double>(data_size) + 1) {  // +1: ASCII may end without newline
      fail(name, "PLY header declares " + std::to_string(element.count) + " " + element.name +
                     " elements but only " + std::to_string(data_size) + " bytes of data follow");
    }
  }
}

// Sequential reader of the PLY body, ASCII tokens or binary values; messages name the element.
class BodyReader {
 public:
  BodyReader(std::string_view data, PlyEncoding encoding, const std::string& name)
      : data_(data), encoding_(encoding), name_(name) {}

  void set_context(const std::string* element, long long index) {
    element_ = element;
    index_ = index;
  }

  double scalar(ScalarType type) {
    return encoding_ == PlyEncoding::ascii ? ascii_scalar(type) : binary_scalar(type);
  }

  // A list length, checked against the bytes left so that a bogus count fails at once.
  long long list_length(ScalarType count_type, ScalarType item_type) {
    const double value = scalar(count_type);
    const size_t least_item = encoding_ == PlyEncoding::ascii ? 2 : type_size(item_type);
    if (value < 0 || value * static_cast<double>(least_item) >
                         static_cast<double>(data_.size() - position_) + 1) {
      error("list length " + std::to_string(static_cast<long long>(value)) +
            " is negative or exceeds the file");
    }
    return static_cast<long long>(value);
  }

  // A provenance value: a hole id or kOriginal, so an integer that an int holds.
  int hole_id(double value) const {
    if (!(std::floor(value) == value && std::abs(value) <= std::numeric_limits<int>::max())) {
      error(std::string(kProvenanceProperty) + " value " + std::to_string(value) +
            " is not a hole id");
    }
    return static_cast<int>(value);
  }

  [[noreturn]] void error(const std::string& what) const {
    fail(name_,
         (element_ ? *element_ + " " + std::to_string(index_) + ": " : std::string()) + what);
  }

 private:
  double ascii_scalar(ScalarType type) {
    while (position_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[position_]))) {
      ++position_;
    }
    size_t end = position_;
    while (end < data_.size() && !std::isspace(static_cast<unsigned char>(data_[end]))) ++end;
    const std::string_view token = data_.substr(position_, end - position_);
    if (token.empty()) error("unexpected end of file");
    position_ = end;
    double value = 0;
    float single = 0;  // float properties are parsed as floats: "0.1" must give the float 0.1
    if (type == ScalarType::float32 ? !parse_number(token, single) : !parse_number(token, value)) {
      error("expected a number, found " + quote(token));
    }
    if (type == ScalarType::float32) value = single;
    const auto [lowest, highest] = value_range(type);
    if (is_integer(type) && !(std::floor(value) == value && value >= lowest && value <= highest)) {
      error("expected an integer of type " + std::string(type_name(type)) + ", found " +
            quote(token));
    }
    return value;
  }

  double binary_scalar(ScalarType type) {
    const size_t size = type_size(type);
    if (data_.size() - position_ < size) error("unexpected end of file");
    unsigned char raw[8];
    std::memcpy(raw, data_.data() + position_, size);
    position_ += size;
    if (encoding_ == PlyEncoding::binary_big_endian) std::reverse(raw, raw + size);
    switch (type) {
      case ScalarType::int8:
        return load<std::int8_t>(raw);
      case ScalarType::uint8:
        return load<std::uint8_t>(raw);
      case ScalarType::int16:
        return load<std::int16_t>(raw);
      case ScalarType::uint16:
        return load<std::uint16_t>(raw);
      case ScalarType::int32:
        return load<std::int32_t>(raw);
      case ScalarType::uint32:
        return load<std::uint32_t>(raw);
      case ScalarType::float32:
        return load<float>(raw);
      case ScalarType::float64:
        return load<double>(raw);
    }
    return 0;
  }

  template <typename T>
  static double load(const unsigned char* raw) {
    T value;
    std::memcpy(&value, raw, sizeof(T));
    return static_cast<double>(value);
  }

  std::string_view data_;
  size_t position_ = 0;
  PlyEncoding encoding_;
  const std::string& name_;
  const std::string* element_ = nullptr;
  long long index_ = 0;
};

// Where each vertex property goes.
enum class VertexSlot { x, y, z, nx, ny, nz, red, green, blue, hole, extra, skip };

VertexSlot vertex_slot(const PlyProperty& property) {
  if (property.is_list) return VertexSlot::skip;
  static const std::pair<const char*, VertexSlot> kNames[] = {
      {"x", VertexSlot::x},       {"y", VertexSlot::y},
      {"z", VertexSlot::z},       {"nx", VertexSlot::nx},
      {"ny", VertexSlot::ny},     {"nz", VertexSlot::nz},
      {"red", VertexSlot::red},   {"green", VertexSlot::green},
      {"blue", VertexSlot::blue}, {kProvenanceProperty, VertexSlot::hole}};
  for (const auto& [text, slot] : kNames) {
    if (property.name == text) {
      // Colours are read as colours when 8-bit or floating point; other types are kept as-is.
      const bool colour =
          slot == VertexSlot::red || slot == VertexSlot::green || slot == VertexSlot::blue;
      if (colour && is_integer(property.type) && property.type != ScalarType::uint8) {
        return VertexSlot::extra;
      }
      return slot;
    }
  }
  return VertexSlot::extra;
}

bool has_slot(const std::vector<VertexSlot>& slots, VertexSlot slot) {
  return std::find(slots.begin(), slots.end(), slot) != slots.end();
}

// The three slots from `first` on (x y z, nx ny nz or red green blue).
bool in_triple(VertexSlot slot, VertexSlot first) {
  return slot >= first && static_cast<int>(slot) < static_cast<int>(first) + 3;
}

// A normal or a colour is read as one only when its three components are there (a colour's of
// one type); otherwise its components are carried through as extra properties, so nothing is lost.
void keep_triple_whole(const PlyElement& element, std::vector<VertexSlot>& slots, VertexSlot first,
                       bool same_type) {
  std::vector<size_t> components;
  for (size_t i = 0; i < slots.size(); ++i) {
    if (in_triple(slots[i], first)) components.push_back(i);
  }
  bool whole = components.size() == 3;
  for (size_t i : components) {
    whole = whole && (!same_type ||
                      element.properties[i].type == element.properties[components.front()].type);
  }
  if (whole) return;
  for (size_t i : components) slots[i] = VertexSlot::extra;
}

// The type a triple is written back in: float32 when its three components are, else float64
// (integer coordinates too: generated vertices need fractions).
ScalarType real_storage(const PlyElement& element, const std::vector<VertexSlot>& slots,
                        VertexSlot first) {
  bool single = true;
  for (size_t i = 0; i < slots.size(); ++i) {
    if (in_triple(slots[i], first))
      single = single && element.properties[i].type == ScalarType::float32;
  }
  return single ? ScalarType::float32 : ScalarType::float64;
}

// The slot of each vertex property, the mesh's storage types set from them and an extra property
// made for each that rangefill does not interpret (its index in `extra_index`).
std::vector<VertexSlot> vertex_slots(const PlyElement& element, BodyReader& body,
                                     ReadResult& result, const std::string& name,
                                     std::vector<int>& extra_index) {
  Mesh& mesh = result.mesh;
  std::vector<VertexSlot> slots;
  for (const PlyProperty& property : element.properties) slots.push_back(vertex_slot(property));
  for (VertexSlot required : {VertexSlot::x, VertexSlot::y, VertexSlot::z}) {
    if (!has_slot(slots, required)) body.error("vertex element lacks x, y or z");
  }
  keep_triple_whole(element, slots, VertexSlot::nx, false);
  keep_triple_whole(element, slots, VertexSlot::red, true);
  mesh.storage.position = real_storage(element, slots, VertexSlot::x);
  mesh.storage.normal = real_storage(element, slots, VertexSlot::nx);
  extra_index.assign(element.properties.size(), -1);
  for (size_t i = 0; i < element.properties.size(); ++i) {
    const PlyProperty& property = element.properties[i];
    if (slots[i] == VertexSlot::red) mesh.storage.color = property.type;
    if (slots[i] == VertexSlot::extra) {
      extra_index[i] = static_cast<int>(mesh.vertex_properties.size());
      mesh.vertex_properties.push_back({property.name, property.type, {}});
      mesh.vertex_properties.back().values.reserve(element.count);
    }
    if (slots[i] == VertexSlot::skip) {
      result.warnings.push_back(name + ": vertex list property '" + property.name + "' ignored");
    }
  }
  return slots;
}

void read_vertices(const PlyElement& element, BodyReader& body, ReadResult& result,
                   const std::string& name) {
  Mesh& mesh = result.mesh;
  std::vector<int> extra_index;
  const std::vector<VertexSlot> slots = vertex_slots(element, body, result, name, extra_index);
  const bool normals = has_slot(slots, VertexSlot::nx) && has_slot(slots, VertexSlot::ny) &&
                       has_slot(slots, VertexSlot::nz);
  const bool colors = has_slot(slots, VertexSlot::red) && has_slot(slots, VertexSlot::green) &&
                      has_slot(slots, VertexSlot::blue);
  const double color_scale = is_integer(mesh.storage.color) ? 1.0 / 255.0 : 1.0;

  mesh.positions.reserve(element.count);
  if (normals) mesh.normals.reserve(element.count);
  if (colors) mesh.colors.reserve(element.count);
  mesh.vertex_hole.reserve(element.count);
  for (long long v = 0; v < element.count; ++v) {
    body.set_context(&element.name, v);
    Vec3 position = Vec3::Zero(), normal = Vec3::Zero();
    Eigen::Vector3d color = Eigen::Vector3d::Zero();
    int hole = kOriginal;
    for (size_t i = 0; i < element.properties.size(); ++i) {
      const PlyProperty& property = element.properties[i];
      if (slots[i] == VertexSlot::skip) {
        const long long length = body.list_length(property.count_type, property.type);
        for (long long k = 0; k < length; ++k) body.scalar(property.type);
        continue;
      }
      const double value = body.scalar(property.type);
      switch (slots[i]) {
        case VertexSlot::x:
          position.x() = value;
          break;
        case VertexSlot::y:
          position.y() = value;
          break;
        case VertexSlot::z:
          position.z() = value;
          break;
        case VertexSlot::nx:
          normal.x() = value;
          break;
        case VertexSlot::ny:
          normal.y() = value;
          break;
        case VertexSlot::nz:
          normal.z() = value;
          break;
        case VertexSlot::red:
          color.x() = value * color_scale;
          break;
        case VertexSlot::green:
          color.y() = value * color_scale;
          break;
        case VertexSlot::blue:
          color.z() = value * color_scale;
          break;
        case VertexSlot::hole:
          hole = body.hole_id(value);
          break;
        case VertexSlot::extra:
          mesh.vertex_properties[extra_index[i]].values.push_back(value);
          break;
        case VertexSlot::skip:
          break;
      }
    }
    mesh.positions.push_back(position);
    if (normals) mesh.normals.push_back(normal);
    if (colors) mesh.colors.push_back(color.cast<float>());
    mesh.vertex_hole.push_back(hole);
  }
  body.set_context(nullptr, 0);
}

void read_faces(const PlyElement& element, BodyReader& body, ReadResult& result,
                const std::string& name) {
  Mesh& mesh = result.mesh;
  int indices = -1, hole = -1;
  std::vector<int> extra_index(element.properties.size(), -1);
  for (size_t i = 0; i < element.properties.size(); ++i) {
    const PlyProperty& property = element.properties[i];
    if (property.is_list &&
        (property.name == "vertex_indices" || property.name == "vertex_index")) {
      if (indices < 0 && is_integer(property.type)) indices = static_cast<int>(i);
    } else if (!property.is_list && property.name == kProvenanceProperty) {
      hole = static_cast<int>(i);
    } else if (property.name == "vertex_indices" || property.name == "vertex_index") {
      // Carried through, it would be written beside the index list under the list's own name.
      fail(name, "face property '" + property.name + "' is not an integer list of vertices");
    } else if (!property.is_list) {
      extra_index[i] = static_cast<int>(mesh.face_properties.size());
      mesh.face_properties.push_back({property.name, property.type, {}});
    } else {
      result.warnings.push_back(name + ": face list property '" + property.name + "' ignored");
    }
  }
  if (indices < 0) fail(name, "face element has no integer vertex_indices list");

  FaceBuilder faces(result, name);
  std::vector<long long> polygon;
  std::vector<double> values(element.properties.size());
  mesh.triangles.reserve(element.count);
  mesh.face_hole.reserve(element.count);
  for (long long f = 0; f < element.count; ++f) {
    body.set_context(&element.name, f);
    for (size_t i = 0; i < element.properties.size(); ++i) {
      const PlyProperty& property = element.properties[i];
      if (!property.is_list) {
        values[i] = body.scalar(property.type);
        continue;
      }
      const long long length = body.list_length(property.count_type, property.type);
      if (static_cast<int>(i) == indices) polygon.clear();
      for (long long k = 0; k < length; ++k) {
        const double index = body.scalar(property.type);
        if (static_cast<int>(i) == indices) polygon.push_back(static_cast<long long>(index));
      }
    }
    const int triangles = faces.add(polygon, f);
    for (int t = 0; t < triangles; ++t) {
      mesh.face_hole.push_back(hole >= 0 ? body.hole_id(values[hole]) : kOriginal);
      for (size_t i = 0; i < element.properties.size(); ++i) {
        if (extra_index[i] >= 0) mesh.face_properties[extra_index[i]].values.push_back(values[i]);
      }
    }
  }
  faces.finish();
  body.set_context(nullptr, 0);
}

void skip_element(const PlyElement& element, BodyReader& body) {
  for (long long e = 0; e < element.count; ++e) {
    body.set_context(&element.name, e);
    for (const PlyProperty& property : element.properties) {
      const long long length =
          property.is_list ? body.list_length(property.count_type, property.type) : 1;
      for (long long k = 0; k < length; ++k) body.scalar(property.type);
    }
  }
  body.set_context(nullptr, 0);
}

}  // namespace

ReadResult parse_ply(std::string_view bytes, const std::string& name) {
  const PlyHeader header = parse_header(bytes, name);
  const std::string_view data = bytes.substr(header.data_offset);
  check_counts_fit(header, data.size(), name);

  ReadResult result;
  BodyReader body(data, header.encoding, name);
  bool have_vertices = false, have_faces = false;
  for (const PlyElement& element : header.elements) {
    if (element.name == "vertex" && !have_vertices) {
      read_vertices(element, body, result, name);
      have_vertices = true;
    } else if (element.name == "face" && !have_faces) {
      if (!have_vertices) fail(name, "PLY face element comes before the vertex element");
      read_faces(element, body, result, name);
      have_faces = true;
    } else {
      skip_element(element, body);
      if (element.count > 0) {
        result.warnings.push_back(name + ": PLY element '" + element.name + "' (" +
                                  std::to_string(element.count) + ") ignored");
      }
    }
  }
  if (!have_vertices) fail(name, "PLY file has no vertex element");
  result.mesh.face_hole.resize(result.mesh.triangles.size(), kOriginal);
  return result;
}

// ------------------------------------------------------------------------------------------------
// Writing

namespace {

class BodyWriter {
 public:
  BodyWriter(ByteSink& sink, PlyEncoding encoding)
      : sink_(sink), out_(sink.bytes()), encoding_(encoding) {}

  void scalar(double value, ScalarType type) {
    if (encoding_ == PlyEncoding::ascii) {
      if (!at_line_start_) out_ += ' ';
      append_number(out_, value, type);
      at_line_start_ = false;
      return;
    }
    switch (type) {
      case ScalarType::int8:
        store(static_cast<std::int8_t>(value));
        break;
      case ScalarType::uint8:
        store(static_cast<std::uint8_t>(value));
        break;
      case ScalarType::int16:
        store(static_cast<std::int16_t>(value));
        break;
      case ScalarType::uint16:
        store(static_cast<std::uint16_t>(value));
        break;
      case ScalarType::int32:
        store(static_cast<std::int32_t>(value));
        break;
      case ScalarType::uint32:
        store(static_cast<std::uint32_t>(value));
        break;
      case ScalarType::float32:
        store(static_cast<float>(value));
        break;
      case ScalarType::float64:
        store(value);
        break;
    }
  }

  void end_record() {
    if (encoding_ == PlyEncoding::ascii) out_ += '\n';
    at_line_start_ = true;
    sink_.end_record();
  }

 private:
  template <typename T>
  void store(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (encoding_ == PlyEncoding::binary_big_endian) std::reverse(raw, raw + sizeof(T));
    out_.append(raw, sizeof(T));
  }

  ByteSink& sink_;
  std::string& out_;  // the sink's
  PlyEncoding encoding_;
  bool at_line_start_ = true;
};

bool any_generated(const std::vector<int>& provenance) {
  return std::any_of(provenance.begin(), provenance.end(), [](int h) { return h != kOriginal; });
}

// 8-bit colours go back to their integer values exactly; floating-point ones as stored.
double color_channel(float value, ScalarType type) {
  return is_integer(type) ? std::clamp(std::round(value * 255.0), 0.0, 255.0) : value;
}

}  // namespace

void serialize_ply(const Mesh& mesh, const WriteOptions& options, ByteSink& sink) {
  const PlyEncoding encoding = options.encoding == Encoding::ascii ? PlyEncoding::ascii
                               : options.big_endian                ? PlyEncoding::binary_big_endian
                                                    : PlyEncoding::binary_little_endian;
  const bool provenance =
      options.provenance && (any_generated(mesh.vertex_hole) || any_generated(mesh.face_hole));
  const ScalarType color_type =
      is_integer(mesh.storage.color) ? ScalarType::uint8 : mesh.storage.color;

  std::string& out = sink.bytes();
  out += "ply\nformat ";
  out += encoding == PlyEncoding::ascii               ? "ascii"
         : encoding == PlyEncoding::binary_big_endian ? "binary_big_endian"
                                                      : "binary_little_endian";
  out += " 1.0\ncomment written by rangefill\n";
  if (provenance) {
    out += std::string("comment ") + kProvenanceProperty +
           ": -1 = from the input, k >= 0 = generated when filling hole k\n";
  }
  size_t record_bytes = 0;  // of the element being declared, in binary
  auto property = [&out, &record_bytes](ScalarType type, const std::string& name) {
    out += std::string("property ") + type_name(type) + " " + name + "\n";
    record_bytes += type_size(type);
  };
  out += "element vertex " + std::to_string(mesh.vertex_count()) + "\n";
  for (const char* axis : {"x", "y", "z"}) property(mesh.storage.position, axis);
  if (mesh.has_normals()) {
    for (const char* axis : {"nx", "ny", "nz"}) property(mesh.storage.normal, axis);
  }
  if (mesh.has_colors()) {
    for (const char* channel : {"red", "green", "blue"}) property(color_type, channel);
  }
  for (const ExtraProperty& extra : mesh.vertex_properties) property(extra.type, extra.name);
  if (provenance) property(ScalarType::int32, kProvenanceProperty);
  const size_t vertex_bytes = record_bytes;
  out += "element face " + std::to_string(mesh.face_count()) + "\n";
  out += "property list uchar int vertex_indices\n";
  record_bytes = type_size(ScalarType::uint8) + 3 * type_size(ScalarType::int32);
  for (const ExtraProperty& extra : mesh.face_properties) property(extra.type, extra.name);
  if (provenance) property(ScalarType::int32, kProvenanceProperty);
  out += "end_header\n";
  if (encoding != PlyEncoding::ascii) {  // the body's exact size: the string grows once
    sink.expect(mesh.vertex_count() * vertex_bytes + mesh.face_count() * record_bytes);
  }

  BodyWriter body(sink, encoding);
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    for (int axis = 0; axis < 3; ++axis)
      body.scalar(mesh.positions[v][axis], mesh.storage.position);
    if (mesh.has_normals()) {
      for (int axis = 0; axis < 3; ++axis) body.scalar(mesh.normals[v][axis], mesh.storage.normal);
    }
    if (mesh.has_colors()) {
      for (int c = 0; c < 3; ++c)
        body.scalar(color_channel(mesh.colors[v][c], color_type), color_type);
    }
    for (const ExtraProperty& extra : mesh.vertex_properties)
      body.scalar(extra.values[v], extra.type);
    if (provenance) body.scalar(mesh.vertex_hole[v], ScalarType::int32);
    body.end_record();
  }
  for (int f = 0; f < mesh.face_count(); ++f) {
    body.scalar(3, ScalarType::uint8);
    for (int corner : mesh.triangles[f]) body.scalar(corner, ScalarType::int32);
    for (const ExtraProperty& extra : mesh.face_properties)
      body.scalar(extra.values[f], extra.type);
    if (provenance) body.scalar(mesh.face_hole[f], ScalarType::int32);
    body.end_record();
  }
}

}  // namespace rangefill::detail
