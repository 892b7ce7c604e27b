#include "rangefill/io/mesh_io.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "io/formats.h"

namespace rangefill {

namespace fs = std::filesystem;

MeshFormat format_from_extension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".ply") return MeshFormat::ply;
  if (extension == ".obj") return MeshFormat::obj;
  if (extension == ".off") return MeshFormat::off;
  if (extension == ".stl") return MeshFormat::stl;
  throw InvalidInput(path.string() + ": unknown mesh format '" + extension +
                     "' (expected .ply, .obj, .off or .stl)");
}

ReadResult parse_mesh(std::string_view bytes, MeshFormat format, const std::string& name) {
  ReadResult result;
  switch (format) {
    case MeshFormat::ply:
      result = detail::parse_ply(bytes, name);
      break;
    case MeshFormat::obj:
      result = detail::parse_obj(bytes, name);
      break;
    case MeshFormat::off:
      result = detail::parse_off(bytes, name);
      break;
    case MeshFormat::stl:
      result = detail::parse_stl(bytes, name);
      break;
  }
  if (result.mesh.positions.empty()) {
    // A text file named .obj reads as an OBJ file without statements: not a mesh at all.
    detail::fail(name, format == MeshFormat::obj ? "no vertex ('v' line): not an OBJ mesh"
                                                 : "holds no vertices: nothing to read as a mesh");
  }
  validate_mesh(result.mesh, name);
  return result;
}

std::string read_file(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw IoError(path.string() + ": cannot open: " + std::strerror(errno));
  std::error_code error;
  if (fs::is_directory(path, error)) throw IoError(path.string() + ": is a directory");
  // One read of the whole file (a character iterator is slow); a file that grows meanwhile is
  // read to its end.
  file.seekg(0, std::ios::end);
  const std::streamoff size = file.tellg();
  file.seekg(0, std::ios::beg);
  std::string bytes(size > 0 ? static_cast<size_t>(size) : 0, '\0');
  file.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<size_t>(file.gcount()));
  if (file.bad()) throw IoError(path.string() + ": read error");
  bytes.append(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  return bytes;
}

namespace {

// The bytes of a regular file, read into pages of their own (an anonymous mapping) that go back
// to the system once parsed: read into the heap, a large file would leave a hole as large as
// itself that the arrays made later do not fit in, and the process's resident size would keep
// it. Other files (pipes, a file that grows meanwhile) as read_file reads them, and opened there
// only: a pipe opened twice loses what its writer wrote and closed in between, and waits for a
// writer that never comes.
class FileBytes {
 public:
  explicit FileBytes(const fs::path& path) {
    struct stat status {};
    const bool regular =
        ::stat(path.c_str(), &status) == 0 && S_ISREG(status.st_mode) && status.st_size > 0;
    const int fd = regular ? ::open(path.c_str(), O_RDONLY | O_CLOEXEC) : -1;
    if (fd >= 0) {
      size_ = static_cast<size_t>(status.st_size);
      void* pages =
          ::mmap(nullptr, size_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (pages != MAP_FAILED) {
        pages_ = static_cast<char*>(pages);
        ::madvise(pages_, size_, MADV_HUGEPAGE);  // 2 MB a fault, not 4 KB
        if (!read_exactly(fd)) release();
      }
      ::close(fd);
    }
    if (!pages_) copy_ = read_file(path);
  }
  ~FileBytes() { release(); }
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;

  std::string_view bytes() const { return pages_ ? std::string_view(pages_, size_) : copy_; }

 private:
  // Whether the file held size_ bytes, no more.
  bool read_exactly(int fd) {
    size_t done = 0;
    while (done < size_) {
      const ssize_t n = ::read(fd, pages_ + done, size_ - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      done += static_cast<size_t>(n);
    }
    char more;
    return ::read(fd, &more, 1) == 0;
  }
  void release() {
    if (pages_) ::munmap(pages_, size_);
    pages_ = nullptr;
  }

  char* pages_ = nullptr;
  size_t size_ = 0;
  std::string copy_;
};

}  // namespace

ReadResult read_mesh(const fs::path& path, const ReadOptions& options) {
  const MeshFormat format = format_from_extension(path);
  ReadResult result = [&] {
    const FileBytes file(path);
    if (file.bytes().empty()) throw InvalidInput(path.string() + ": file is empty");
    return parse_mesh(file.bytes(), format, path.string());
  }();
  if (options.spare_share > 0) {
    reserve_more(result.mesh, static_cast<int>(options.spare_share * result.mesh.vertex_count()),
                 static_cast<int>(options.spare_share * result.mesh.face_count()));
  }
  return result;
}

namespace {

void serialize(const Mesh& mesh, MeshFormat format, const WriteOptions& options,
               detail::ByteSink& sink) {
  switch (format) {
    case MeshFormat::ply:
      return detail::serialize_ply(mesh, options, sink);
    case MeshFormat::obj:
      return detail::serialize_obj(mesh, sink);
    case MeshFormat::off:
      return detail::serialize_off(mesh, sink);
    case MeshFormat::stl:
      return detail::serialize_stl(mesh, options, sink);
  }
}

// Writes all of `bytes` to `fd`; 0 or the errno of the failure.
int write_all(int fd, std::string_view bytes) {
  size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    written += static_cast<size_t>(n);
  }
  return 0;
}

// Writes what `produce` gives to `fd` and syncs it; 0 or the errno of the first failure. Closes
// `fd` if `produce` throws.
int write_produced(int fd, const ByteProducer& produce) {
  int error = 0;
  try {
    produce([&](std::string_view bytes) {
      if (error == 0) error = write_all(fd, bytes);
    });
  } catch (...) {
    ::close(fd);
    throw;
  }
  return error == 0 && ::fsync(fd) != 0 ? errno : error;
}

}  // namespace

std::string serialize_mesh(const Mesh& mesh, MeshFormat format, const WriteOptions& options) {
  detail::ByteSink sink;
  serialize(mesh, format, options, sink);
  return sink.take();
}

void write_file_atomically(const std::string& bytes, const fs::path& path) {
  write_file_atomically(path, [&](const auto& write) { write(bytes); });
}

void write_file_atomically(const fs::path& path, const ByteProducer& produce) {
  static std::atomic<unsigned> counter{0};
  const fs::path directory = path.has_parent_path() ? path.parent_path() : fs::path(".");
  const fs::path temporary =
      directory / ("." + path.filename().string() + ".rangefill-" + std::to_string(::getpid()) +
                   "-" + std::to_string(counter++) + ".tmp");
  // An unnamed file (O_TMPFILE) while the bytes are written: a process that dies meanwhile, even
  // by SIGKILL, leaves nothing behind. It gets the temporary name only to be renamed at once.
  // Where the file system has no O_TMPFILE (or /proc is missing), a named temporary file is used.
  int error = 0;
  bool linked = false;
  const int unnamed = ::open(directory.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (unnamed >= 0) {
    error = write_produced(unnamed, produce);
    const std::string self = "/proc/self/fd/" + std::to_string(unnamed);
    linked = error == 0 &&
             ::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, temporary.c_str(), AT_SYMLINK_FOLLOW) == 0;
    if (::close(unnamed) != 0 && error == 0) error = errno;
  }
  if (error == 0 && !linked) {
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) throw IoError(path.string() + ": cannot create file: " + std::strerror(errno));
    try {
      error = write_produced(fd, produce);
    } catch (...) {
      ::unlink(temporary.c_str());
      throw;
    }
    if (::close(fd) != 0 && error == 0) error = errno;
  }
  if (error == 0 && ::rename(temporary.c_str(), path.c_str()) != 0) error = errno;
  if (error != 0) {
    ::unlink(temporary.c_str());
    throw IoError(path.string() + ": cannot write: " + std::strerror(error));
  }
}

void write_mesh(const Mesh& mesh, const fs::path& path, const WriteOptions& options) {
  validate_mesh(mesh, path.string());
  const MeshFormat format = format_from_extension(path);
  write_file_atomically(path, [&](const auto& write) {
    detail::ByteSink sink(write);
    serialize(mesh, format, options, sink);
    sink.flush();
  });
}

namespace detail {

void fail(const std::string& name, const std::string& what) {
  throw InvalidInput(name + ": " + what);
}

void fail_at(const std::string& name, long long line, const std::string& what) {
  fail(name, "line " + std::to_string(line) + ": " + what);
}

std::string quote(std::string_view token) {
  constexpr size_t kMaxLength = 40;
  std::string quoted = "'";
  for (size_t i = 0; i < std::min(token.size(), kMaxLength); ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    quoted += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  if (token.size() > kMaxLength) quoted += "...";
  return quoted + "'";
}

int FaceBuilder::add(const std::vector<long long>& polygon, long long file_face, long long line) {
  const std::string face =
      (line > 0 ? "line " + std::to_string(line) + ": face " : "face ") + std::to_string(file_face);
  if (polygon.size() < 3) fail(name_, face + " has fewer than 3 vertices");
  const long long vertex_count = result_.mesh.vertex_count();
  corners_.clear();
  for (long long index : polygon) {
    if (index < 0 || index >= vertex_count) {
      fail(name_, face + " refers to vertex " + std::to_string(index) + ", out of range [0, " +
                      std::to_string(vertex_count) + ")");
    }
    if (std::find(corners_.begin(), corners_.end(), index) != corners_.end()) {
      fail(name_, face + " repeats vertex " + std::to_string(index));
    }
    corners_.push_back(static_cast<int>(index));
  }
  std::vector<Triangle>& triangles = result_.mesh.triangles;
  if (corners_.size() == 3) {
    triangles.push_back({corners_[0], corners_[1], corners_[2]});
    return 1;
  }
  ++polygons_triangulated_;
  const std::vector<Triangle> pieces = triangulate_polygon(result_.mesh.positions, corners_);
  triangles.insert(triangles.end(), pieces.begin(), pieces.end());
  return static_cast<int>(pieces.size());
}

void FaceBuilder::finish() {
  if (polygons_triangulated_ > 0) {
    result_.warnings.push_back(name_ + ": " + std::to_string(polygons_triangulated_) +
                               " polygons with more than 3 vertices were triangulated");
  }
  result_.mesh.face_hole.reserve(result_.mesh.triangles.size());
  result_.mesh.face_hole.resize(result_.mesh.triangles.size(), kOriginal);
}

void append_number(std::string& out, double value, ScalarType type) {
  char buffer[64];
  std::to_chars_result end{};
  switch (type) {
    case ScalarType::float32:
      end = std::to_chars(buffer, buffer + sizeof buffer, static_cast<float>(value));
      break;
    case ScalarType::float64:
      end = std::to_chars(buffer, buffer + sizeof buffer, value);
      break;
    default:
      end = std::to_chars(buffer, buffer + sizeof buffer, static_cast<long long>(value));
      break;
  }
  out.append(buffer, end.ptr);
}

void append_numbers(std::string& out, const Vec3& values, ScalarType type) {
  append_number(out, values.x(), type);
  out += ' ';
  append_number(out, values.y(), type);
  out += ' ';
  append_number(out, values.z(), type);
}

bool TokenReader::next_line(char comment) {
  while (position_ < text_.size()) {
    const size_t end = std::min(text_.find('\n', position_), text_.size());
    line_ = text_.substr(position_, end - position_);
    position_ = std::min(end + 1, text_.size());
    ++line_number_;
    const size_t hash = line_.find(comment);
    if (hash != std::string_view::npos) line_ = line_.substr(0, hash);
    while (!line_.empty() && std::isspace(static_cast<unsigned char>(line_.back()))) {
      line_.remove_suffix(1);
    }
    while (!line_.empty() && std::isspace(static_cast<unsigned char>(line_.front()))) {
      line_.remove_prefix(1);
    }
    if (!line_.empty()) return true;
  }
  line_ = {};
  return false;
}

std::string_view TokenReader::token() {
  size_t begin = 0;
  while (begin < line_.size() && std::isspace(static_cast<unsigned char>(line_[begin]))) ++begin;
  size_t end = begin;
  while (end < line_.size() && !std::isspace(static_cast<unsigned char>(line_[end]))) ++end;
  const std::string_view result = line_.substr(begin, end - begin);
  line_.remove_prefix(end);
  return result;
}

}  // namespace detail
}  // namespace rangefill
