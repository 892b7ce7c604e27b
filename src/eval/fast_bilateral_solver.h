// Internal: OpenCV contrib's fast bilateral solver (ximgproc, Barron & Poole 2016) as a depth
// filling peer, in a module of its own, librangefill_fbs.so, beside librangefill_eval.so, which
// eval/baselines.cpp loads (dlopen) on first use: ximgproc and the libraries it links (dnn,
// calib3d, imgcodecs, ...) load only then.
#pragma once

#include <opencv2/core.hpp>

namespace rangefill::fbs {

constexpr const char* kModule = "librangefill_fbs.so";
constexpr const char* kEntry = "rangefill_fast_bilateral_solver";

/// The module's entry: cv::ximgproc::fastBilateralSolverFilter of `depth` (CV_16UC1 mm) guided by
/// `color` (CV_8UC3), the valid pixels outside `to_fill` as confidence 1, into `out` (CV_16UC1).
using Entry = void (*)(const cv::Mat& depth, const cv::Mat& color, const cv::Mat& to_fill,
                       cv::Mat& out);

}  // namespace rangefill::fbs
