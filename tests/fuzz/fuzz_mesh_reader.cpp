// libFuzzer target for one mesh reader, chosen at compile time by RANGEFILL_FUZZ_FORMAT (ply, obj,
// off or stl). What must hold for any bytes: parse_mesh either returns a mesh that passes
// validate_mesh and survives a write and a re-read with its counts, or throws InvalidInput with a
// one-line message naming the file. Anything else (a crash, a sanitizer report, another exception,
// an allocation beyond -malloc_limit_mb) is a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "rangefill/core/errors.h"
#include "rangefill/io/mesh_io.h"

namespace {

constexpr rangefill::MeshFormat kFormat = rangefill::MeshFormat::RANGEFILL_FUZZ_FORMAT;
constexpr const char* kName = "fuzz-input";

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_mesh_reader: %s\n", what.c_str());
  std::abort();
}

void check_message(const rangefill::InvalidInput& error) {
  const std::string_view message = error.what();
  if (message.find('\n') != std::string_view::npos) finding("message of several lines");
  if (message.substr(0, std::char_traits<char>::length(kName)) != kName) {
    finding("message does not start with the file name: " + std::string(message));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  rangefill::ReadResult read;
  try {
    read = rangefill::parse_mesh(bytes, kFormat, kName);
  } catch (const rangefill::InvalidInput& error) {
    check_message(error);
    return 0;
  }
  for (const std::string& warning : read.warnings) {
    if (warning.find('\n') != std::string::npos) finding("warning of several lines");
  }
  // What was read can be written and read back with the same counts.
  const std::string written = rangefill::serialize_mesh(read.mesh, kFormat);
  rangefill::ReadResult again;
  try {
    again = rangefill::parse_mesh(written, kFormat, kName);
  } catch (const rangefill::InvalidInput& error) {
    finding(std::string("what was written does not read back: ") + error.what());
  }
  if (again.mesh.face_count() != read.mesh.face_count()) finding("face count changed on re-read");
  if (kFormat != rangefill::MeshFormat::stl &&
      again.mesh.vertex_count() != read.mesh.vertex_count()) {
    finding("vertex count changed on re-read");  // STL keeps only the vertices of faces
  }
  return 0;
}
