// Internal: PNG, TIFF and EXR images in memory, through libpng, libtiff and OpenEXR (the last two
// in a module loaded when first needed, io/tiff_exr.h). Not installed.
//
// OpenCV's imgcodecs would do the same, but it loads many shared libraries (GDAL, Poppler, HEIF,
// ...) when a program starts, a cost every run of the rangefill program would pay.
#pragma once

#include <string>
#include <string_view>

#include <opencv2/core.hpp>

namespace rangefill::detail {

/// The PNG, TIFF or EXR image in `bytes`, as stored: 8-bit, 16-bit or float samples, its channels
/// (colour in OpenCV's BGR order). Throws InvalidInput("<name>: ...") on anything else or a
/// corrupt file.
cv::Mat decode_image(std::string_view bytes, const std::string& name);

/// The same, and JPEG (8-bit grey or BGR): what a colour camera writes.
cv::Mat decode_color_image(std::string_view bytes, const std::string& name);

/// `image` encoded as the format of `extension` (".png", ".tif", ".tiff" or ".exr"): PNG holds 8-
/// or 16-bit samples, 1 or 3 channels (BGR); TIFF 8-bit, 16-bit or float, one channel; EXR float,
/// one channel ("Y"). Throws InvalidInput("<name>: ...") for an image the format cannot hold.
std::string encode_image(const cv::Mat& image, const std::string& extension,
                         const std::string& name);

}  // namespace rangefill::detail
