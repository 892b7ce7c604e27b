// Depth-filling peers that rangefill depth-bench measures beside fill_depth.
#pragma once

#include <opencv2/core.hpp>

namespace rangefill {

/// OpenCV contrib's fast bilateral solver (cv::ximgproc::fastBilateralSolverFilter, Barron &
/// Poole 2016, its default parameters), the colour-guided filter a vision engineer tries first:
/// `depth` (CV_16UC1 mm, 0 invalid) solved with `color` (CV_8UC3, same size) as the guide and the
/// valid pixels outside `to_fill` (CV_8UC1) as confidence 1, every other pixel 0. Returns `depth`
/// with the pixels of `to_fill` replaced. Loads the module that links ximgproc on first use;
/// throws ProcessingError when it cannot.
cv::Mat fill_depth_fast_bilateral_solver(const cv::Mat& depth, const cv::Mat& color,
                                         const cv::Mat& to_fill);

}  // namespace rangefill
