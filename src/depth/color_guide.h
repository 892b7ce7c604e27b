// The colour image that guides fill_depth (DepthFillOptions::color): how alike two pixels look.
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "rangefill/inpaint/harmonic.h"

namespace rangefill {

/// The colour difference (8-bit units, Euclidean over B, G, R) at which two pixels count as
/// different surfaces: affinities fall off over it as in a joint-bilateral filter.
constexpr float kColorSigma = 10;

/// guide_affinity at kColorSigma.
inline float color_affinity(const cv::Vec3f& a, const cv::Vec3f& b) {
  return guide_affinity(a, b, kColorSigma);
}

/// `color` (CV_8UC3 BGR or RGB, CV_8UC1 grey, the depth's `size`) as CV_32FC3, grey replicated;
/// empty for an empty `color`. Throws InvalidInput naming `who` on another type or size.
cv::Mat guide_color(const cv::Mat& color, cv::Size size, const std::string& who);

}  // namespace rangefill
