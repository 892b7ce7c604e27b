// Reading and writing meshes: PLY (ASCII, binary either endianness), OBJ, OFF, STL (ASCII, binary).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "rangefill/core/mesh.h"

namespace rangefill {

enum class MeshFormat { ply, obj, off, stl };

/// The format named by a file's extension (case-insensitive); throws InvalidInput if unknown.
MeshFormat format_from_extension(const std::filesystem::path& path);

/// A mesh as read, with the warnings met on the way (polygons triangulated, properties dropped).
struct ReadResult {
  Mesh mesh;
  std::vector<std::string> warnings;
};

struct ReadOptions {
  /// Room left in every array of the mesh for this share more vertices and faces (0: none), for a
  /// caller that appends to them without moving them; taken once the file is parsed and its bytes
  /// released.
  double spare_share = 0;
};

/// Reads a mesh whose format is given by the extension. Vertex order, faces and per-vertex colours
/// and normals are kept; polygons are triangulated (with a warning). The result passes
/// validate_mesh. Throws IoError (cannot read) or InvalidInput (malformed; the message names the
/// file and the problem). Memory is bounded by a small multiple of the file size whatever counts a
/// header declares.
ReadResult read_mesh(const std::filesystem::path& path, const ReadOptions& options = {});

/// Parses a mesh from memory; `name` is used in messages. What read_mesh does after loading the
/// file.
ReadResult parse_mesh(std::string_view bytes, MeshFormat format, const std::string& name);

/// The whole content of a file. Throws IoError when it cannot be opened or read, or is a directory.
std::string read_file(const std::filesystem::path& path);

/// Writes `bytes` to a fresh temporary file beside `path`, then renames it over `path`, so that a
/// failure leaves no partial file and a reader never sees one. The temporary file has no name
/// while it is written (O_TMPFILE, where the file system has it): a process killed meanwhile
/// leaves nothing behind. Throws IoError.
void write_file_atomically(const std::string& bytes, const std::filesystem::path& path);

/// What gives write_file_atomically a file's bytes in pieces: it calls `write` on each in order.
using ByteProducer = std::function<void(const std::function<void(std::string_view)>& write)>;

/// As above, the bytes from `produce`, so that a large file is never whole in memory. `produce`
/// runs again if the unnamed file cannot be given a name (no /proc).
void write_file_atomically(const std::filesystem::path& path, const ByteProducer& produce);

enum class Encoding { binary, ascii };

struct WriteOptions {
  Encoding encoding = Encoding::binary;  // OBJ and OFF are always ASCII
  bool big_endian = false;               // binary PLY only
  bool provenance = true;                // PLY only: the `rangefill_hole` vertex/face property
};

/// Writes atomically: to a temporary file beside `path`, then renamed over it, so that a failure
/// leaves no partial file; the bytes go out a megabyte at a time as they are made. Positions,
/// normals and colours are written in mesh.storage types (ASCII with enough digits to read back
/// the same value). Throws IoError.
void write_mesh(const Mesh& mesh, const std::filesystem::path& path,
                const WriteOptions& options = {});

/// The bytes write_mesh would write.
std::string serialize_mesh(const Mesh& mesh, MeshFormat format, const WriteOptions& options = {});

}  // namespace rangefill
