// The module librangefill_tiff_exr.so (io/tiff_exr.h): the only translation unit that includes
// libtiff and OpenEXR.
#include "io/tiff_exr.h"

#include <tiffio.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <vector>

#include "io/codec_limits.h"

namespace rangefill::detail::tiff_exr {

namespace {

// --- TIFF (libtiff) ---------------------------------------------------------------------------

// A TIFF file in memory: what libtiff's client procedures read, or write to.
struct TiffBuffer {
  std::string bytes;
  toff_t at = 0;
  std::string error;
};

tmsize_t tiff_read(thandle_t handle, void* out, tmsize_t count) {
  auto* buffer = static_cast<TiffBuffer*>(handle);
  const toff_t available =
      buffer->at < buffer->bytes.size() ? buffer->bytes.size() - buffer->at : 0;
  const toff_t copied = std::min<toff_t>(available, static_cast<toff_t>(count));
  std::memcpy(out, buffer->bytes.data() + buffer->at, copied);
  buffer->at += copied;
  return static_cast<tmsize_t>(copied);
}

tmsize_t tiff_write(thandle_t handle, void* data, tmsize_t count) {
  auto* buffer = static_cast<TiffBuffer*>(handle);
  if (buffer->bytes.size() < buffer->at + count) buffer->bytes.resize(buffer->at + count);
  std::memcpy(buffer->bytes.data() + buffer->at, data, count);
  buffer->at += count;
  return count;
}

toff_t tiff_seek(thandle_t handle, toff_t offset, int whence) {
  auto* buffer = static_cast<TiffBuffer*>(handle);
  const toff_t base = whence == SEEK_CUR   ? buffer->at
                      : whence == SEEK_END ? buffer->bytes.size()
                                           : 0;
  buffer->at = base + offset;
  return buffer->at;
}

int tiff_close(thandle_t) {
  return 0;
}

toff_t tiff_size(thandle_t handle) {
  return static_cast<TiffBuffer*>(handle)->bytes.size();
}

int tiff_map(thandle_t, void**, toff_t*) {
  return 0;
}

void tiff_unmap(thandle_t, void*, toff_t) {}

int tiff_error(TIFF*, void* user_data, const char* module, const char* format, va_list args) {
  auto* buffer = static_cast<TiffBuffer*>(user_data);
  if (buffer->error.empty()) {
    char text[256];
    std::vsnprintf(text, sizeof(text), format, args);
    buffer->error = one_line(std::string(module ? module : "libtiff") + ": " + text);
  }
  return 1;  // handled: libtiff prints nothing
}

int tiff_warning(TIFF*, void*, const char*, const char*, va_list) {
  return 1;
}

// The buffer opened by libtiff ("r" or "w"), its errors and warnings kept off stderr; reading
// allocates within allocation_limit.
TIFF* open_tiff(TiffBuffer& buffer, const char* mode, const std::string& name) {
  TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
  TIFFOpenOptionsSetErrorHandlerExtR(options, tiff_error, &buffer);
  TIFFOpenOptionsSetWarningHandlerExtR(options, tiff_warning, &buffer);
  if (mode[0] == 'r') {
    TIFFOpenOptionsSetMaxSingleMemAlloc(options,
                                        static_cast<tmsize_t>(allocation_limit(buffer.bytes)));
  }
  TIFF* tiff = TIFFClientOpenExt(name.c_str(), mode, &buffer, tiff_read, tiff_write, tiff_seek,
                                 tiff_close, tiff_size, tiff_map, tiff_unmap, options);
  TIFFOpenOptionsFree(options);
  return tiff;
}

// Closes the TIFF when it goes out of scope.
struct TiffCloser {
  TIFF* tiff;
  ~TiffCloser() { TIFFClose(tiff); }
};

cv::Mat decode_tiff(std::string_view bytes, const std::string& name) {
  TiffBuffer buffer;
  buffer.bytes.assign(bytes);
  TIFF* tiff = open_tiff(buffer, "r", name);
  if (!tiff) throw InvalidInput(name + ": corrupt TIFF: " + buffer.error);
  const TiffCloser closer{tiff};
  std::uint32_t width = 0, height = 0;
  std::uint16_t samples = 1, bits = 1, format = SAMPLEFORMAT_UINT, planar = PLANARCONFIG_CONTIG;
  TIFFGetField(tiff, TIFFTAG_IMAGEWIDTH, &width);
  TIFFGetField(tiff, TIFFTAG_IMAGELENGTH, &height);
  TIFFGetFieldDefaulted(tiff, TIFFTAG_SAMPLESPERPIXEL, &samples);
  TIFFGetFieldDefaulted(tiff, TIFFTAG_BITSPERSAMPLE, &bits);
  TIFFGetFieldDefaulted(tiff, TIFFTAG_SAMPLEFORMAT, &format);
  TIFFGetFieldDefaulted(tiff, TIFFTAG_PLANARCONFIG, &planar);
  int depth = -1;
  if (format == SAMPLEFORMAT_UINT && bits == 8) depth = CV_8U;
  if (format == SAMPLEFORMAT_UINT && bits == 16) depth = CV_16U;
  if (format == SAMPLEFORMAT_IEEEFP && bits == 32) depth = CV_32F;
  if (depth < 0 || samples < 1 || samples > 4 || (samples > 1 && planar != PLANARCONFIG_CONTIG)) {
    throw InvalidInput(name + ": TIFF of " + std::to_string(samples) + " samples of " +
                       std::to_string(bits) + " bits (format " + std::to_string(format) +
                       "): expected unsigned 8 or 16 bits or 32-bit float");
  }
  const size_t pixel_bytes = static_cast<size_t>(samples) * bits / 8;
  check_size(width, height, static_cast<double>(pixel_bytes), bytes, name);
  cv::Mat image(static_cast<int>(height), static_cast<int>(width), CV_MAKETYPE(depth, samples));
  if (TIFFIsTiled(tiff)) {
    std::uint32_t tile_width = 0, tile_height = 0;
    TIFFGetField(tiff, TIFFTAG_TILEWIDTH, &tile_width);
    TIFFGetField(tiff, TIFFTAG_TILELENGTH, &tile_height);
    if (tile_width == 0 || tile_height == 0) throw InvalidInput(name + ": TIFF tiles of size 0");
    check_size(tile_width, tile_height, static_cast<double>(pixel_bytes), bytes, name);
    const size_t tile_row = static_cast<size_t>(tile_width) * pixel_bytes;
    const tmsize_t tile_bytes = TIFFTileSize(tiff);
    if (tile_bytes < 0 || static_cast<size_t>(tile_bytes) < tile_row * tile_height) {
      throw InvalidInput(name + ": corrupt TIFF: tiles smaller than their size says");
    }
    std::vector<unsigned char> tile(static_cast<size_t>(tile_bytes));
    for (std::uint32_t y = 0; y < height; y += tile_height) {
      for (std::uint32_t x = 0; x < width; x += tile_width) {
        if (TIFFReadTile(tiff, tile.data(), x, y, 0, 0) < 0) {
          throw InvalidInput(name + ": corrupt TIFF: " + buffer.error);
        }
        const std::uint32_t rows = std::min(tile_height, height - y);
        const std::uint32_t columns = std::min(tile_width, width - x);
        for (std::uint32_t r = 0; r < rows; ++r) {
          std::memcpy(image.ptr(static_cast<int>(y + r)) + x * pixel_bytes,
                      tile.data() + r * tile_row, columns * pixel_bytes);
        }
      }
    }
  } else {
    for (std::uint32_t y = 0; y < height; ++y) {
      if (TIFFReadScanline(tiff, image.ptr(static_cast<int>(y)), y, 0) < 0) {
        throw InvalidInput(name + ": corrupt TIFF: " + buffer.error);
      }
    }
  }
  if (samples == 3) cv::cvtColor(image, image, cv::COLOR_RGB2BGR);
  if (samples == 4) cv::cvtColor(image, image, cv::COLOR_RGBA2BGRA);
  return image;
}

std::string encode_tiff(const cv::Mat& image, const std::string& name) {
  const int depth = image.depth();
  if ((depth != CV_8U && depth != CV_16U && depth != CV_32F) || image.channels() != 1 ||
      image.empty()) {
    throw InvalidInput(name + ": TIFF is written with one channel of 8 or 16 bits or float, not " +
                       cv::typeToString(image.type()));
  }
  TiffBuffer buffer;
  TIFF* tiff = open_tiff(buffer, "w", name);
  if (!tiff) throw IoError(name + ": libtiff could not start a file: " + buffer.error);
  {
    const TiffCloser closer{tiff};
    TIFFSetField(tiff, TIFFTAG_IMAGEWIDTH, static_cast<std::uint32_t>(image.cols));
    TIFFSetField(tiff, TIFFTAG_IMAGELENGTH, static_cast<std::uint32_t>(image.rows));
    TIFFSetField(tiff, TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(tiff, TIFFTAG_BITSPERSAMPLE, static_cast<int>(8 * image.elemSize()));
    TIFFSetField(tiff, TIFFTAG_SAMPLEFORMAT,
                 depth == CV_32F ? SAMPLEFORMAT_IEEEFP : SAMPLEFORMAT_UINT);
    TIFFSetField(tiff, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
    TIFFSetField(tiff, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(tiff, TIFFTAG_COMPRESSION, COMPRESSION_LZW);  // as OpenCV writes TIFF
    TIFFSetField(tiff, TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(tiff, 0));
    for (int y = 0; y < image.rows; ++y) {
      if (TIFFWriteScanline(tiff, const_cast<uchar*>(image.ptr(y)), y, 0) < 0) {
        throw IoError(name + ": libtiff could not encode the image: " + buffer.error);
      }
    }
  }
  return buffer.bytes;
}

// --- EXR (OpenEXR) ----------------------------------------------------------------------------

// The little-endian 32-bit integer at `at`.
std::int32_t little_endian(std::string_view bytes, size_t at) {
  std::uint32_t value = 0;
  for (int k = 3; k >= 0; --k) value = value << 8 | static_cast<unsigned char>(bytes[at + k]);
  return static_cast<std::int32_t>(value);
}

// Whether an attribute value of a type OpenEXR knows has the size OpenEXR will read: it reads
// those by their structure, not by the size the file gives (a mismatch would put the next
// attribute elsewhere for OpenEXR than for us), and reserves what a preview or a vector declares.
// Other types OpenEXR keeps as opaque bytes, reserved by the size given.
bool exr_value_fits(std::string_view type, std::string_view value) {
  static const std::map<std::string_view, size_t> fixed = {{"box2i", 16},
                                                           {"box2f", 16},
                                                           {"chromaticities", 32},
                                                           {"compression", 1},
                                                           {"deepImageState", 1},
                                                           {"double", 8},
                                                           {"envmap", 1},
                                                           {"float", 4},
                                                           {"int", 4},
                                                           {"keycode", 28},
                                                           {"lineOrder", 1},
                                                           {"m33f", 36},
                                                           {"m33d", 72},
                                                           {"m44f", 64},
                                                           {"m44d", 128},
                                                           {"rational", 8},
                                                           {"tiledesc", 9},
                                                           {"timecode", 8},
                                                           {"v2i", 8},
                                                           {"v2f", 8},
                                                           {"v2d", 16},
                                                           {"v3i", 12},
                                                           {"v3f", 12},
                                                           {"v3d", 24}};
  if (const auto known = fixed.find(type); known != fixed.end()) {
    return value.size() == known->second;
  }
  if (type == "chlist") {  // entries (name, pixel type, linear, 3 reserved, x and y sampling), ""
    size_t at = 0;
    for (;;) {
      const size_t end = value.find('\0', at);
      if (end == std::string_view::npos || end - at > 255) return false;
      if (end == at) return end + 1 == value.size();
      at = end + 1 + 16;
      if (at > value.size()) return false;
    }
  }
  if (type == "preview") {  // width, height, then 4 bytes a pixel
    return value.size() >= 8 && 8 + 4.0 * static_cast<std::uint32_t>(little_endian(value, 0)) *
                                            static_cast<std::uint32_t>(little_endian(value, 4)) ==
                                    static_cast<double>(value.size());
  }
  if (type == "stringvector") {  // strings, each after its length
    for (size_t at = 0; at < value.size();) {
      if (value.size() - at < 4) return false;
      const std::int32_t length = little_endian(value, at);
      if (length < 0 || static_cast<size_t>(length) > value.size() - at - 4) return false;
      at += 4 + static_cast<size_t>(length);
    }
    return true;
  }
  if (type == "floatvector") return value.size() % 4 == 0;
  return type != "idmanifest";  // compressed, with its own declared size: not read
}

// The number of channels in a chlist value that exr_value_fits accepted.
int exr_channel_count(std::string_view chlist) {
  int count = 0;
  for (size_t at = 0; chlist[at] != '\0'; at = chlist.find('\0', at) + 1 + 16) ++count;
  return count;
}

// The scan lines OpenEXR's decompressor for a compression attribute reserves at once, however few
// the image has (OpenEXR's numLinesInBuffer; the most of them for a value it does not know).
double exr_lines_per_block(unsigned char compression) {
  constexpr std::array<double, 10> lines = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
  return compression < lines.size() ? lines[compression] : 256;
}

// Walks a single-part EXR header (magic, version, then attributes: name, type, size, value, up to
// an empty name) before OpenEXR reads it: OpenEXR reserves what an attribute's size, the data
// window or its compression's block of scan lines declares before it checks the file holds it.
// Throws InvalidInput unless every attribute lies within the file, there is one channel, and the
// data window, a block of its lines and a tile fit the limits (check_size, 4 bytes a pixel).
void check_exr_header(std::string_view bytes, const std::string& name) {
  const auto corrupt = [&](const std::string& why) {
    throw InvalidInput(name + ": corrupt EXR: " + why);
  };
  if (bytes.size() < 8) corrupt("file is truncated");
  const std::int32_t version = little_endian(bytes, 4);
  if (version & 0x1800) corrupt("multi-part and deep images are not read");
  // Names of at most 31 characters, 255 with the long-names flag: OpenEXR reads no more, and
  // would take the rest of a longer one for the next field.
  const size_t longest = version & 0x400 ? 255 : 31;
  size_t at = 8;
  const auto text = [&]() {  // a null-terminated name
    const size_t end = bytes.find('\0', at);
    if (end == std::string_view::npos) corrupt("header is truncated");
    if (end - at > longest) corrupt("a name is longer than " + std::to_string(longest));
    const std::string_view word = bytes.substr(at, end - at);
    at = end + 1;
    return word;
  };
  bool window = false;
  double width = 0;
  double height = 0;
  double lines_per_block = 1;
  int channels = 0;
  for (;;) {
    const std::string_view attribute = text();
    if (attribute.empty()) break;
    const std::string_view type = text();
    if (bytes.size() - at < 4) corrupt("header is truncated");
    const std::int32_t size = little_endian(bytes, at);
    at += 4;
    if (size < 0 || static_cast<size_t>(size) > bytes.size() - at) {
      corrupt("an attribute runs past the end of the file");
    }
    const std::string_view value = bytes.substr(at, static_cast<size_t>(size));
    if (!exr_value_fits(type, value)) {
      corrupt("an attribute of type " + std::string(type) + " does not fit its size");
    }
    if (attribute == "dataWindow" && type == "box2i") {
      width = static_cast<double>(little_endian(value, 8)) - little_endian(value, 0) + 1;
      height = static_cast<double>(little_endian(value, 12)) - little_endian(value, 4) + 1;
      window = true;
    }
    if (attribute == "compression" && type == "compression") {
      lines_per_block = exr_lines_per_block(static_cast<unsigned char>(value[0]));
    }
    if (attribute == "channels" && type == "chlist") channels = exr_channel_count(value);
    if (attribute == "tiles" && type == "tiledesc") {  // a tile's buffer is reserved whole
      check_size(static_cast<std::uint32_t>(little_endian(value, 0)),
                 static_cast<std::uint32_t>(little_endian(value, 4)), sizeof(float), bytes, name);
    }
    at += static_cast<size_t>(size);
  }
  if (!window) corrupt("no data window");
  check_size(width, height, sizeof(float), bytes, name);
  check_size(width, std::max(height, lines_per_block), sizeof(float), bytes, name);
  if (channels != 1) {
    throw InvalidInput(name + ": has " + std::to_string(channels) +
                       " channels; a depth or mask image has one");
  }
}

cv::Mat decode_exr(std::string_view bytes, const std::string& name) {
  check_exr_header(bytes, name);
  try {
    Imf::StdISStream stream;
    stream.str(std::string(bytes));
    Imf::InputFile file(stream);
    const Imath::Box2i window = file.header().dataWindow();
    const double width = static_cast<double>(window.max.x) - window.min.x + 1;
    const double height = static_cast<double>(window.max.y) - window.min.y + 1;
    const std::string channel = file.header().channels().begin().name();
    cv::Mat image(static_cast<int>(height), static_cast<int>(width), CV_32FC1);
    Imf::FrameBuffer frame;
    // The slice's origin is the data window's: the buffer's first pixel is (min.x, min.y).
    char* origin =
        reinterpret_cast<char*>(image.ptr<float>()) -
        (static_cast<ptrdiff_t>(window.min.x) + static_cast<ptrdiff_t>(window.min.y) * image.cols) *
            static_cast<ptrdiff_t>(sizeof(float));
    frame.insert(channel, Imf::Slice(Imf::FLOAT, origin, sizeof(float), image.step[0]));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const InvalidInput&) {
    throw;
  } catch (const std::exception& error) {
    throw InvalidInput(name + ": corrupt EXR: " + one_line(error.what()));
  }
}

std::string encode_exr(const cv::Mat& image, const std::string& name) {
  if (image.type() != CV_32FC1 || image.empty()) {
    throw InvalidInput(name + ": EXR is written as one float channel, not " +
                       cv::typeToString(image.type()));
  }
  try {
    Imf::StdOSStream stream;
    Imf::Header header(image.cols, image.rows);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(stream, header);
    Imf::FrameBuffer frame;
    frame.insert("Y", Imf::Slice(Imf::FLOAT, const_cast<char*>(image.ptr<char>()), sizeof(float),
                                 image.step[0]));
    file.setFrameBuffer(frame);
    file.writePixels(image.rows);
    return stream.str();
  } catch (const std::exception& error) {
    throw IoError(name + ": OpenEXR could not encode the image: " + one_line(error.what()));
  }
}

cv::Mat decode(std::string_view bytes, const std::string& name, Format format) {
  return format == Format::tiff ? decode_tiff(bytes, name) : decode_exr(bytes, name);
}

std::string encode(const cv::Mat& image, const std::string& name, Format format) {
  return format == Format::tiff ? encode_tiff(image, name) : encode_exr(image, name);
}

}  // namespace

}  // namespace rangefill::detail::tiff_exr

extern "C" __attribute__((visibility("default")))
const rangefill::detail::tiff_exr::Codecs rangefill_tiff_exr_codecs{
    rangefill::detail::tiff_exr::decode, rangefill::detail::tiff_exr::encode};
