// Depth and mask image files: 16-bit PNG or TIFF in millimetres, float TIFF or EXR in metres
// (conventions: depth/depth_image.h); written atomically. Read and written with libpng, libtiff and
// OpenEXR (not OpenCV's imgcodecs, whose many shared libraries a program would load at start).
#pragma once

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace rangefill {

/// Reads a depth image: 16-bit PNG or TIFF (CV_16UC1, millimetres), float TIFF or EXR (CV_32FC1,
/// metres), one channel. Throws IoError when the file cannot be read, InvalidInput when it is not
/// such an image; the message names the file.
cv::Mat read_depth_image(const std::filesystem::path& path);

/// Reads a mask image of any depth, one channel: CV_8UC1, 255 where the file is non-zero.
cv::Mat read_mask_image(const std::filesystem::path& path);

/// Reads the colour image that guides a depth fill: PNG, TIFF or JPEG, 8-bit grey (CV_8UC1) or
/// colour (CV_8UC3, BGR). Throws InvalidInput naming the file otherwise.
cv::Mat read_color_image(const std::filesystem::path& path);

/// Writes a mask (CV_8UC1) as an 8-bit PNG or TIFF, by the extension, atomically. Throws
/// InvalidInput (another type or extension) or IoError, naming the file.
void write_mask_image(const cv::Mat& mask, const std::filesystem::path& path);

/// `image` as a PNG file's bytes: 8- or 16-bit samples, 1 or 3 channels (BGR, as OpenCV keeps
/// colour). Throws InvalidInput for another type.
std::string encode_png(const cv::Mat& image);

/// True when the extension of `path` (any case) is one of the depth image formats: .png, .tif,
/// .tiff, .exr.
bool is_depth_image_path(const std::filesystem::path& path);

/// Throws InvalidInput naming `path` unless its extension (.png, .tif, .tiff, .exr) can hold depth
/// of `type`: PNG CV_16UC1, TIFF both, EXR CV_32FC1.
void check_depth_format(const std::filesystem::path& path, int type);

/// Writes a depth image in the format of the extension (check_depth_format), atomically
/// (write_file_atomically). Throws InvalidInput or IoError naming the file.
void write_depth_image(const cv::Mat& depth, const std::filesystem::path& path);

}  // namespace rangefill
