#include "rangefill/io/depth_io.h"

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "io/image_codecs.h"
#include "rangefill/core/depth_image.h"
#include "rangefill/core/errors.h"
#include "rangefill/io/mesh_io.h"

namespace rangefill {

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// The image in a file, as stored, with one channel.
cv::Mat decode_single_channel(const fs::path& path) {
  const std::string bytes = read_file(path);
  if (bytes.empty()) throw InvalidInput(path.string() + ": file is empty");
  cv::Mat image = detail::decode_image(bytes, path.string());
  if (image.channels() != 1) {
    throw InvalidInput(path.string() + ": has " + std::to_string(image.channels()) +
                       " channels; a depth or mask image has one");
  }
  return image;
}

}  // namespace

cv::Mat read_depth_image(const fs::path& path) {
  cv::Mat image = decode_single_channel(path);
  if (image.type() != CV_16UC1 && image.type() != CV_32FC1) {
    throw InvalidInput(path.string() + ": " + cv::typeToString(image.type()) +
                       " is not depth: expected 16-bit unsigned (millimetres) or 32-bit float "
                       "(metres)");
  }
  return image;
}

cv::Mat read_mask_image(const fs::path& path) {
  return decode_single_channel(path) != 0;
}

cv::Mat read_color_image(const fs::path& path) {
  const std::string bytes = read_file(path);
  if (bytes.empty()) throw InvalidInput(path.string() + ": file is empty");
  cv::Mat image = detail::decode_color_image(bytes, path.string());
  if (image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3)) {
    throw InvalidInput(path.string() + ": " + cv::typeToString(image.type()) +
                       " is not a colour image: expected 8-bit grey or colour (RGB)");
  }
  return image;
}

bool is_depth_image_path(const fs::path& path) {
  const std::string extension = lower_extension(path);
  return extension == ".png" || extension == ".tif" || extension == ".tiff" || extension == ".exr";
}

void check_depth_format(const fs::path& path, int type) {
  check_depth_type(type, path.string());
  if (!is_depth_image_path(path)) {
    throw InvalidInput(path.string() + ": unknown depth image format '" +
                       path.extension().string() + "' (expected .png, .tif, .tiff or .exr)");
  }
  const std::string extension = lower_extension(path);
  if (extension == ".png" && type != CV_16UC1) {
    throw InvalidInput(path.string() +
                       ": PNG holds 16-bit depth only; write float depth to .tif or .exr");
  }
  if (extension == ".exr" && type != CV_32FC1) {
    throw InvalidInput(path.string() +
                       ": EXR holds float depth only; write 16-bit depth to .png or .tif");
  }
}

namespace {

// Encodes `image` in the format of `path`'s extension and writes it atomically.
void encode_and_write(const cv::Mat& image, const fs::path& path) {
  write_file_atomically(detail::encode_image(image, lower_extension(path), path.string()), path);
}

}  // namespace

void write_depth_image(const cv::Mat& depth, const fs::path& path) {
  check_depth_format(path, depth.type());
  encode_and_write(depth, path);
}

std::string encode_png(const cv::Mat& image) {
  return detail::encode_image(image, ".png", "PNG image");
}

void write_mask_image(const cv::Mat& mask, const fs::path& path) {
  const std::string extension = lower_extension(path);
  if (mask.type() != CV_8UC1) {
    throw InvalidInput(path.string() + ": a mask is CV_8UC1, not " + cv::typeToString(mask.type()));
  }
  if (extension != ".png" && extension != ".tif" && extension != ".tiff") {
    throw InvalidInput(path.string() + ": a mask is written as .png, .tif or .tiff");
  }
  encode_and_write(mask, path);
}

}  // namespace rangefill
