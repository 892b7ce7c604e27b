// Depth images as rangefill reads them.
//
// Conventions: CV_16UC1 depth is in millimetres and CV_32FC1 depth in metres, both the distance
// along the optical axis (z, not the length of the ray). A pixel is invalid when its depth is 0,
// negative or not finite; 16-bit files hold 0 there, float files 0 or NaN.
#pragma once

#include <algorithm>
#include <string>

#include <opencv2/core.hpp>

namespace rangefill {

/// Throws InvalidInput, `who` first, unless `type` is CV_16UC1 or CV_32FC1.
void check_depth_type(int type, const std::string& who);

/// Depth (CV_16UC1 or CV_32FC1) in metres, CV_32FC1, 0 where invalid.
cv::Mat depth_in_metres(cv::InputArray depth);

/// The pixels fill_depth reads as invalid: CV_8UC1, 255 where depth (CV_16UC1 or CV_32FC1) is 0,
/// negative or not finite.
cv::Mat invalid_depth_mask(cv::InputArray depth);

/// Depths a, b (any unit, > 0) lie on one surface unless the larger exceeds the smaller by more
/// than `discontinuity` (relative): the depth jump of an occluding edge.
inline bool same_surface(float a, float b, double discontinuity) {
  return std::max(a, b) <= (1 + discontinuity) * std::min(a, b);
}

}  // namespace rangefill
