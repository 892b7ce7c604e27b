#include "io/image_codecs.h"

#include <png.h>
// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>
#include <cstdio>

#include <algorithm>
#include <array>
#include <csetjmp>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <vector>

#include "core/module_loader.h"
#include "io/codec_limits.h"
#include "io/png_check.h"
#include "io/tiff_exr.h"
#include "rangefill/core/errors.h"

namespace rangefill::detail {

namespace {

// --- PNG (libpng) -----------------------------------------------------------------------------

// libpng reports errors by a longjmp from its error callback; the message is kept here.
struct PngContext {
  std::string_view bytes;
  size_t at = 0;
  std::string* output = nullptr;
  std::vector<png_bytep> rows;  // here, not a local: a longjmp may clobber locals set after setjmp
  char error[256] = "";
};

void png_failed(png_structp png, png_const_charp message) {
  auto* context = static_cast<PngContext*>(png_get_error_ptr(png));
  std::snprintf(context->error, sizeof(context->error), "%s", message);
  png_longjmp(png, 1);
}

void png_warned(png_structp, png_const_charp) {}

void png_read_bytes(png_structp png, png_bytep out, size_t count) {
  auto* context = static_cast<PngContext*>(png_get_io_ptr(png));
  if (count > context->bytes.size() - context->at) png_error(png, "file is truncated");
  std::memcpy(out, context->bytes.data() + context->at, count);
  context->at += count;
}

void png_write_bytes(png_structp png, png_bytep data, size_t count) {
  static_cast<PngContext*>(png_get_io_ptr(png))
      ->output->append(reinterpret_cast<char*>(data), count);
}

void png_flush_nothing(png_structp) {}

// Decodes into `image` (allocated once the header is read); returns false with context.error set
// on failure. No C++ object with a destructor lives in this frame across the longjmp.
bool decode_png_into(PngContext& context, cv::Mat& image) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &context, png_failed, png_warned);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    std::snprintf(context.error, sizeof(context.error), "out of memory");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_read_fn(png, &context, png_read_bytes);
  png_read_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info);
  const png_uint_32 height = png_get_image_height(png, info);
  const int bit_depth = png_get_bit_depth(png, info);
  const int colour_type = png_get_color_type(png, info);
  if (colour_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (bit_depth == 16) png_set_swap(png);  // to the machine's byte order (little-endian)
  if (colour_type & PNG_COLOR_MASK_COLOR) png_set_bgr(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const int channels = png_get_channels(png, info);
  const int depth = png_get_bit_depth(png, info) == 16 ? CV_16U : CV_8U;
  if (static_cast<double>(width) * height > kMaxPixels) png_error(png, "image too large");
  image.create(static_cast<int>(height), static_cast<int>(width), CV_MAKETYPE(depth, channels));
  context.rows.resize(height);
  for (png_uint_32 y = 0; y < height; ++y) context.rows[y] = image.ptr(static_cast<int>(y));
  png_read_image(png, context.rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

cv::Mat decode_png(std::string_view bytes, const std::string& name) {
  check_png(bytes, name);
  PngContext context;
  context.bytes = bytes;
  cv::Mat image;
  if (!decode_png_into(context, image)) {
    throw InvalidInput(name + ": corrupt PNG: " + one_line(context.error));
  }
  return image;
}

std::string encode_png(const cv::Mat& image, const std::string& name) {
  const int depth = image.depth(), channels = image.channels();
  if ((depth != CV_8U && depth != CV_16U) || (channels != 1 && channels != 3) || image.empty()) {
    throw InvalidInput(name + ": PNG holds 8- or 16-bit images of 1 or 3 channels, not " +
                       cv::typeToString(image.type()));
  }
  std::string output;
  PngContext context;
  context.output = &output;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &context, png_failed, png_warned);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw IoError(name + ": out of memory encoding a PNG");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw IoError(name + ": libpng could not encode the image: " + one_line(context.error));
  }
  png_set_write_fn(png, &context, png_write_bytes, png_flush_nothing);
  png_set_IHDR(png, info, image.cols, image.rows, depth == CV_16U ? 16 : 8,
               channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 1);  // OpenCV's default for PNG: fast, most of the gain
  png_write_info(png, info);
  if (depth == CV_16U) png_set_swap(png);
  if (channels == 3) png_set_bgr(png);
  for (int y = 0; y < image.rows; ++y) {
    png_write_row(png, const_cast<png_bytep>(image.ptr(y)));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return output;
}

// --- JPEG (libjpeg) ----------------------------------------------------------------------------

// libjpeg reports errors through error_exit, which must not return: a longjmp back to the decoder.
struct JpegErrors {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = "";
};

void jpeg_failed(j_common_ptr jpeg) {
  auto* errors = reinterpret_cast<JpegErrors*>(jpeg->err);
  (*jpeg->err->format_message)(jpeg, errors->message);
  std::longjmp(errors->jump, 1);
}

void jpeg_warned(j_common_ptr /*jpeg*/, int /*level*/) {}

// Decodes into `image` (CV_8UC3 BGR or CV_8UC1); false with errors.message set on a corrupt file.
bool decode_jpeg_into(std::string_view bytes, const std::string& name, JpegErrors& errors,
                      jpeg_decompress_struct& jpeg, cv::Mat& image) {
  if (setjmp(errors.jump)) return false;
  jpeg_create_decompress(&jpeg);
  jpeg_mem_src(&jpeg, reinterpret_cast<const unsigned char*>(bytes.data()),
               static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&jpeg, TRUE);
  const bool grey = jpeg.num_components == 1;
  jpeg.out_color_space = grey ? JCS_GRAYSCALE : JCS_EXT_BGR;
  check_size(jpeg.image_width, jpeg.image_height, grey ? 1 : 3, bytes, name);
  jpeg_start_decompress(&jpeg);
  image.create(static_cast<int>(jpeg.output_height), static_cast<int>(jpeg.output_width),
               grey ? CV_8UC1 : CV_8UC3);
  while (jpeg.output_scanline < jpeg.output_height) {
    JSAMPROW row = image.ptr(static_cast<int>(jpeg.output_scanline));
    jpeg_read_scanlines(&jpeg, &row, 1);
  }
  jpeg_finish_decompress(&jpeg);
  return true;
}

cv::Mat decode_jpeg(std::string_view bytes, const std::string& name) {
  JpegErrors errors;
  jpeg_decompress_struct jpeg{};
  jpeg.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = jpeg_failed;
  errors.manager.emit_message = jpeg_warned;
  cv::Mat image;
  bool decoded = false;
  try {
    decoded = decode_jpeg_into(bytes, name, errors, jpeg, image);
  } catch (...) {  // check_size: a size the bytes cannot hold
    jpeg_destroy_decompress(&jpeg);
    throw;
  }
  jpeg_destroy_decompress(&jpeg);
  if (!decoded) throw InvalidInput(name + ": corrupt JPEG: " + one_line(errors.message));
  return image;
}

// The TIFF and EXR codecs, from their module (io/tiff_exr.h), loaded on the first call.
const tiff_exr::Codecs& tiff_exr_codecs() {
  static const tiff_exr::Codecs codecs = *reinterpret_cast<const tiff_exr::Codecs*>(
      module_entry(tiff_exr::kModule, tiff_exr::kEntry,
                   reinterpret_cast<const void*>(&decode_image), "TIFF and EXR images"));
  return codecs;
}

bool starts_with(std::string_view bytes, std::string_view prefix) {
  return bytes.substr(0, prefix.size()) == prefix;
}

}  // namespace

cv::Mat decode_image(std::string_view bytes, const std::string& name) {
  if (starts_with(bytes, std::string_view("\x89PNG\r\n\x1a\n", 8))) return decode_png(bytes, name);
  if (starts_with(bytes, std::string_view("II*\0", 4)) ||
      starts_with(bytes, std::string_view("MM\0*", 4)) ||
      starts_with(bytes, std::string_view("II+\0", 4)) ||
      starts_with(bytes, std::string_view("MM\0+", 4))) {  // classic and BigTIFF
    return tiff_exr_codecs().decode(bytes, name, tiff_exr::Format::tiff);
  }
  if (starts_with(bytes, "\x76\x2f\x31\x01")) {
    return tiff_exr_codecs().decode(bytes, name, tiff_exr::Format::exr);
  }
  throw InvalidInput(name + ": not a PNG, TIFF or EXR image");
}

cv::Mat decode_color_image(std::string_view bytes, const std::string& name) {
  if (starts_with(bytes, "\xff\xd8\xff")) return decode_jpeg(bytes, name);
  return decode_image(bytes, name);
}

std::string encode_image(const cv::Mat& image, const std::string& extension,
                         const std::string& name) {
  if (extension == ".png") return encode_png(image, name);
  if (extension == ".tif" || extension == ".tiff") {
    return tiff_exr_codecs().encode(image, name, tiff_exr::Format::tiff);
  }
  if (extension == ".exr") return tiff_exr_codecs().encode(image, name, tiff_exr::Format::exr);
  throw InvalidInput(name + ": unknown image format '" + extension +
                     "' (expected .png, .tif, .tiff or .exr)");
}

}  // namespace rangefill::detail
