// Sensor-like holes punched into depth maps, for the depth benchmarks.
#pragma once

#include <cstdint>

#include <opencv2/core.hpp>

namespace rangefill {

/// Sensor-like holes for benchmarks, as a share of the valid pixels, about a third of each kind:
///  - blobs: ellipses with semi-axes of 2–10 pixels, anywhere;
///  - shadows: along 10–60 pixels of a depth edge (a jump above `discontinuity` between
///    horizontal neighbours), the far surface left of the near one, over the width a projector
///    right of the camera cannot light: disparity_scale·(1/z_near − 1/z_far) pixels, at least 1
///    (when the frame has no such edge, blobs instead);
///  - dropouts: patches of 50–600 pixels grown at random from a seed within one surface (no jump
///    above `discontinuity` between neighbours), as dark or specular materials return nothing.
struct SensorHoleOptions {
  double fraction = 0.05;  // of the valid pixels
  std::uint64_t seed = 1;
  double discontinuity = 0.05;
  double disparity_scale = 580 * 0.075;  // focal length (pixels) × baseline (m): Kinect v1
};

/// CV_8UC1, 255 at the punched pixels, all of them valid pixels of `depth` (CV_16UC1 or CV_32FC1).
/// Deterministic for a seed.
cv::Mat punch_depth_holes(cv::InputArray depth, const SensorHoleOptions& options = {});

}  // namespace rangefill
