// Internal: TIFF and EXR images in memory, through libtiff and OpenEXR, in a module of their own,
// librangefill_tiff_exr.so, installed beside librangefill.so, which io/image_codecs.cpp loads
// (dlopen) when it first meets either format: their libraries (libtiff's codecs among them)
// load only then. Not installed.
#pragma once

#include <string>
#include <string_view>

#include <opencv2/core.hpp>

namespace rangefill::detail::tiff_exr {

constexpr const char* kModule = "librangefill_tiff_exr.so";
constexpr const char* kEntry = "rangefill_tiff_exr_codecs";  // a Codecs

enum class Format { tiff, exr };

/// The module's codecs, as decode_image and encode_image (io/image_codecs.h) describe them for
/// these formats.
struct Codecs {
  cv::Mat (*decode)(std::string_view bytes, const std::string& name, Format format);
  std::string (*encode)(const cv::Mat& image, const std::string& name, Format format);
};

}  // namespace rangefill::detail::tiff_exr
