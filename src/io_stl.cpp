#include "io_formats.h"

namespace rangefill::detail {

ReadResult parse_stl(std::string_view, const std::string& name) { fail(name, "work in progress"); }

}  // namespace rangefill::detail
namespace rangefill::detail { std::string serialize_stl(const Mesh&, const WriteOptions&) { return {}; } }
