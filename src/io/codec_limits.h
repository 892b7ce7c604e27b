// Internal: what the image codecs (io/image_codecs.cpp, io/tiff_exr.cpp) share: the limits on what
// a file may make them allocate, and the libraries' messages on one line. Not installed.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>

#include "rangefill/core/errors.h"

namespace rangefill::detail {

// OpenCV's limit on an image's pixels (CV_IO_MAX_IMAGE_PIXELS), which io/png_check.h applies to
// PNG headers too.
inline constexpr double kMaxPixels = 1 << 30;
// No allocation is made for more than this many bytes of raw pixels per byte of the file (deflate
// expands at most 1032-fold), beyond a first megabyte: a small file must not make us, libtiff or
// OpenEXR reserve gigabytes for the size its header declares.
inline constexpr double kMaxExpansion = 1024;
inline constexpr double kFreeBytes = 1 << 20;

// A library's message (libpng, libtiff, OpenEXR) on one line: it may quote bytes of the file.
inline std::string one_line(std::string text) {
  std::replace_if(
      text.begin(), text.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; }, ' ');
  return text;
}

inline double allocation_limit(std::string_view bytes) {
  return kFreeBytes + kMaxExpansion * static_cast<double>(bytes.size());
}

// Throws unless width × height pixels of `pixel_bytes` each fit the limits for `bytes`.
inline void check_size(double width, double height, double pixel_bytes, std::string_view bytes,
                       const std::string& name) {
  const std::string size = std::to_string(static_cast<long long>(width)) + "×" +
                           std::to_string(static_cast<long long>(height));
  if (!(width > 0 && height > 0) || width * height > kMaxPixels) {
    throw InvalidInput(name + ": an image of " + size + " pixels is empty or too large");
  }
  if (width * height * pixel_bytes > allocation_limit(bytes)) {
    throw InvalidInput(name + ": declares " + size + " pixels, more than its " +
                       std::to_string(bytes.size()) + " bytes can hold");
  }
}

}  // namespace rangefill::detail
