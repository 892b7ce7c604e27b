#include "io/png_check.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <vector>

#include "rangefill/core/errors.h"

namespace rangefill::detail {

namespace {

constexpr std::string_view kSignature("\x89PNG\r\n\x1a\n", 8);

std::uint32_t big_endian(std::string_view bytes, size_t at) {
  std::uint32_t value = 0;
  for (size_t k = 0; k < 4; ++k) value = value << 8 | static_cast<unsigned char>(bytes[at + k]);
  return value;
}

// Channels of a colour type for the bit depths the PNG specification allows it (0: invalid).
int channels(int colour_type, int bit_depth) {
  const bool small = bit_depth == 1 || bit_depth == 2 || bit_depth == 4;
  switch (colour_type) {
    case 0:  // greyscale
      return small || bit_depth == 8 || bit_depth == 16 ? 1 : 0;
    case 2:  // truecolour
      return bit_depth == 8 || bit_depth == 16 ? 3 : 0;
    case 3:  // indexed
      return small || bit_depth == 8 ? 1 : 0;
    case 4:  // greyscale with alpha
      return bit_depth == 8 || bit_depth == 16 ? 2 : 0;
    case 6:  // truecolour with alpha
      return bit_depth == 8 || bit_depth == 16 ? 4 : 0;
    default:
      return 0;
  }
}

// The rows of the image data, in order: each its byte count, filter byte included (a pass of an
// interlaced image, Adam7, is a sub-image of its own).
struct Row {
  std::uint64_t bytes;
  std::uint64_t count;  // rows of this size in a row
};

std::vector<Row> image_rows(std::uint64_t width, std::uint64_t height, int bits_per_pixel,
                            bool interlaced) {
  auto row_bytes = [&](std::uint64_t columns) { return 1 + (columns * bits_per_pixel + 7) / 8; };
  if (!interlaced) return {{row_bytes(width), height}};
  // Adam7: starting column and row, column and row steps of the seven passes.
  constexpr std::array<std::array<int, 4>, 7> kPasses = {{{0, 0, 8, 8},
                                                          {4, 0, 8, 8},
                                                          {0, 4, 4, 8},
                                                          {2, 0, 4, 4},
                                                          {0, 2, 2, 4},
                                                          {1, 0, 2, 2},
                                                          {0, 1, 1, 2}}};
  std::vector<Row> rows;
  for (const auto& [x0, y0, dx, dy] : kPasses) {
    const std::uint64_t columns =
        width > static_cast<std::uint64_t>(x0) ? (width - x0 + dx - 1) / dx : 0;
    const std::uint64_t count =
        height > static_cast<std::uint64_t>(y0) ? (height - y0 + dy - 1) / dy : 0;
    if (columns > 0 && count > 0) rows.push_back({row_bytes(columns), count});
  }
  return rows;
}

// Walks the inflated image data, checking each row's filter type (0–4).
class RowChecker {
 public:
  explicit RowChecker(std::vector<Row> rows) : rows_(std::move(rows)) {}

  // Consumes `size` bytes; false on a bad filter type or data beyond the last row.
  bool consume(const unsigned char* data, size_t size) {
    for (size_t i = 0; i < size;) {
      if (row_ == rows_.size()) return false;
      if (offset_ == 0 && data[i] > 4) return false;
      const std::uint64_t take = std::min<std::uint64_t>(size - i, rows_[row_].bytes - offset_);
      i += take;
      offset_ += take;
      if (offset_ == rows_[row_].bytes) {
        offset_ = 0;
        if (++done_ == rows_[row_].count) {
          done_ = 0;
          ++row_;
        }
      }
    }
    return true;
  }

  bool complete() const { return row_ == rows_.size(); }

 private:
  std::vector<Row> rows_;
  size_t row_ = 0;
  std::uint64_t done_ = 0;    // rows of rows_[row_] done
  std::uint64_t offset_ = 0;  // bytes of the current row done
};

}  // namespace

bool is_png(std::string_view bytes) {
  return bytes.substr(0, kSignature.size()) == kSignature;
}

namespace {

[[noreturn]] void corrupt_png(const std::string& name, const std::string& why) {
  throw InvalidInput(name + ": corrupt PNG: " + why);
}

// The rows the image data must hold, from a 13-byte IHDR chunk's `data`; throws InvalidInput
// naming `name` for a header that is invalid, indexed or larger than OpenCV reads.
std::vector<Row> rows_of_header(std::string_view data, const std::string& name) {
  const std::uint32_t width = big_endian(data, 0), height = big_endian(data, 4);
  const int bit_depth = static_cast<unsigned char>(data[8]);
  const int colour_type = static_cast<unsigned char>(data[9]);
  const int interlace = static_cast<unsigned char>(data[12]);
  const int count = channels(colour_type, bit_depth);
  if (width == 0 || height == 0 || width > 0x7fffffffu || height > 0x7fffffffu || count == 0 ||
      data[10] != 0 || data[11] != 0 || interlace > 1) {
    corrupt_png(name, "invalid IHDR chunk");
  }
  if (colour_type == 3)
    corrupt_png(name, "indexed colours (a depth or mask image has one channel)");
  // OpenCV's own limits (CV_IO_MAX_IMAGE_WIDTH, _HEIGHT, _PIXELS): it reads nothing larger.
  if (width > (1u << 20) || height > (1u << 20) ||
      std::uint64_t{width} * height > (std::uint64_t{1} << 30)) {
    corrupt_png(name, std::to_string(width) + "x" + std::to_string(height) +
                          " pixels, more than OpenCV reads (2^20 a side, 2^30 in all)");
  }
  return image_rows(width, height, count * bit_depth, interlace == 1);
}

}  // namespace

void check_png(std::string_view bytes, const std::string& name) {
  auto corrupt = [&](const std::string& why) { corrupt_png(name, why); };
  size_t at = kSignature.size();
  bool header = false, ended = false;
  std::vector<Row> rows;
  z_stream stream{};
  if (inflateInit(&stream) != Z_OK) corrupt("zlib cannot start");
  struct Ender {
    z_stream& stream;
    ~Ender() { inflateEnd(&stream); }
  } ender{stream};
  RowChecker checker({});
  bool inflated = false;  // the image data's zlib stream has ended
  int idat_run = 0;       // 0: no IDAT chunk yet, 1: in the run of IDAT chunks, 2: past it
  std::array<unsigned char, 16384> buffer;
  while (!ended) {
    if (bytes.size() - at < 12) corrupt("truncated (no IEND chunk)");
    const std::uint32_t length = big_endian(bytes, at);
    const std::string_view type = bytes.substr(at + 4, 4);
    for (const char c : type) {  // before a message names it
      if (!std::isalpha(static_cast<unsigned char>(c))) corrupt("a chunk type is not 4 letters");
    }
    if (length > 0x7fffffffu || bytes.size() - at - 12 < length) {
      corrupt("chunk '" + std::string(type) + "' runs past the end of the file");
    }
    const std::string_view data = bytes.substr(at + 8, length);
    const auto* typed = reinterpret_cast<const Bytef*>(bytes.data() + at + 4);
    if (crc32(0, typed, static_cast<uInt>(length + 4)) != big_endian(bytes, at + 8 + length)) {
      corrupt("chunk '" + std::string(type) + "' fails its CRC");
    }
    at += 12 + length;
    const bool critical = std::isupper(static_cast<unsigned char>(type[0]));
    if (critical && type != "IHDR" && type != "IDAT" && type != "IEND" && type != "PLTE") {
      corrupt("unknown critical chunk '" + std::string(type) + "'");
    }
    if (header && type == "IHDR") corrupt("a second IHDR chunk");
    if (idat_run == 1 && type != "IDAT") idat_run = 2;
    if (!header) {
      if (type != "IHDR" || length != 13) corrupt("does not start with an IHDR chunk");
      checker = RowChecker(rows_of_header(data, name));
      header = true;
    } else if (type == "IDAT") {
      if (inflated || idat_run == 2) corrupt("image data after the end of its stream");
      idat_run = 1;
      stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
      stream.avail_in = static_cast<uInt>(data.size());
      while (!inflated) {
        stream.next_out = buffer.data();
        stream.avail_out = static_cast<uInt>(buffer.size());
        const int status = inflate(&stream, Z_NO_FLUSH);
        if (status == Z_BUF_ERROR) break;  // no progress without more input: the next IDAT
        if (status != Z_OK && status != Z_STREAM_END) corrupt("image data does not inflate");
        if (!checker.consume(buffer.data(), buffer.size() - stream.avail_out)) {
          corrupt("image data holds a bad row filter or more rows than the header declares");
        }
        inflated = status == Z_STREAM_END;
        if (stream.avail_in == 0 && stream.avail_out > 0) break;  // all of this chunk is out
      }
      if (inflated && stream.avail_in > 0) corrupt("data after the end of the image stream");
    } else if (type == "IEND") {
      ended = true;
    }
  }
  if (!inflated || !checker.complete()) {
    corrupt("image data shorter than the header declares");
  }
}

}  // namespace rangefill::detail
