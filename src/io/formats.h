// Internal: one parser and one serializer per format, and what they share. Not installed.
#pragma once

#include <charconv>
#include <cmath>
#include <functional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "rangefill/core/errors.h"
#include "rangefill/io/mesh_io.h"

namespace rangefill::detail {

ReadResult parse_ply(std::string_view bytes, const std::string& name);
ReadResult parse_obj(std::string_view bytes, const std::string& name);
ReadResult parse_off(std::string_view bytes, const std::string& name);
ReadResult parse_stl(std::string_view bytes, const std::string& name);

/// Where a serializer appends a file's bytes (bytes()): handed to `drain` and emptied each time a
/// record ends past a megabyte, and at flush(); without a drain they stay, the whole file.
class ByteSink {
 public:
  using Drain = std::function<void(std::string_view)>;
  explicit ByteSink(Drain drain = nullptr) : drain_(std::move(drain)) {}

  std::string& bytes() { return bytes_; }
  /// Room for `count` more bytes when they all stay (a binary body's exact size).
  void expect(size_t count) {
    if (!drain_) bytes_.reserve(bytes_.size() + count);
  }
  void end_record() {
    if (bytes_.size() >= kDrainBytes) flush();
  }
  void flush() {
    if (!drain_) return;
    drain_(bytes_);
    bytes_.clear();
  }
  std::string take() { return std::move(bytes_); }

 private:
  static constexpr size_t kDrainBytes = size_t{1} << 20;
  Drain drain_;
  std::string bytes_;
};

void serialize_ply(const Mesh& mesh, const WriteOptions& options, ByteSink& sink);
void serialize_obj(const Mesh& mesh, ByteSink& sink);
void serialize_off(const Mesh& mesh, ByteSink& sink);
void serialize_stl(const Mesh& mesh, const WriteOptions& options, ByteSink& sink);

/// Throws InvalidInput("<name>: <what>").
[[noreturn]] void fail(const std::string& name, const std::string& what);

/// Throws InvalidInput("<name>: line <line>: <what>").
[[noreturn]] void fail_at(const std::string& name, long long line, const std::string& what);

/// `token` in single quotes for a message: at most 40 characters, bytes that are not printable
/// ASCII shown as '?', so that the message stays one readable line.
std::string quote(std::string_view token);

/// Collects the faces of a file: range-checks each polygon's indices against the vertex count
/// (naming the face as numbered in the file), triangulates polygons with more than three corners,
/// and records one warning with their count at the end (finish()).
class FaceBuilder {
 public:
  FaceBuilder(ReadResult& result, const std::string& name) : result_(result), name_(name) {}
  /// Adds polygon number `file_face` (as the file counts faces), read from line `line` when that is
  /// not 0 (messages name it); returns how many triangles it made.
  int add(const std::vector<long long>& polygon, long long file_face, long long line = 0);
  /// Appends the warning about triangulated polygons and fills face provenance.
  void finish();

 private:
  ReadResult& result_;
  const std::string& name_;
  std::vector<int> corners_;
  long long polygons_triangulated_ = 0;
};

/// Shortest decimal text that reads back as the same value of `type`.
void append_number(std::string& out, double value, ScalarType type);

/// append_number for the three components, separated by spaces.
void append_numbers(std::string& out, const Vec3& values, ScalarType type);

/// Reads a number with std::from_chars (locale-independent); false if `text` is not one whole
/// number.
template <typename T>
bool parse_number(std::string_view text, T& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

/// parse_number, or fail_at(name, line, ...) naming `token` if it is not a number of type T (for
/// floating-point T, not a finite one).
template <typename T>
T parse_number_at(std::string_view token, const std::string& name, long long line) {
  T value{};
  if (!parse_number(token, value)) {
    fail_at(name, line,
            quote(token) +
                (std::is_integral_v<T> ? " is not a valid integer" : " is not a valid number"));
  }
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(value)) fail_at(name, line, quote(token) + " is not a finite number");
  }
  return value;
}

/// Splits text into lines and whitespace-separated tokens; tracks the line number for messages.
class TokenReader {
 public:
  explicit TokenReader(std::string_view text) : text_(text) {}
  /// The next non-empty line (comments starting with `comment` removed); false at the end.
  bool next_line(char comment = '#');
  /// The next token of the current line; empty at the end of the line.
  std::string_view token();
  /// Position just after the current line, for formats that switch to binary.
  size_t offset() const { return position_; }
  long long line_number() const { return line_number_; }
  std::string_view line() const { return line_; }

 private:
  std::string_view text_;
  std::string_view line_;
  size_t position_ = 0;
  long long line_number_ = 0;
};

}  // namespace rangefill::detail
