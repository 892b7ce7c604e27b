// From restored pixels back to 3D points (Pérez et al., Section VII, eq. 13).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "rangefill/core/mesh.h"
#include "rangefill/hole/holes.h"
#include "rangefill/image/range_image.h"

namespace rangefill {

/// The restored pixels of one hole as points, in world and frame coordinates.
struct Patch {
  std::vector<Vec3> points;       // world coordinates
  std::vector<cv::Point> pixels;  // (column, row) of each point
  cv::Mat index;                  // CV_32S, per pixel: index into `points`, or -1
  std::vector<Rgb> colors;        // per point when the mesh has colours (patch_colors), else empty
};

struct BackProjectionOptions {
  double boundary_clearance =
      0.5;  // points closer than this many q to the hole boundary are dropped
};

/// Maps every hole pixel of `image` whose restored value in `restored` (CV_32F) is finite through
/// the inverse normalisation and the inverse plane transform (eq. 13) to a world point, keeping
/// those at least boundary_clearance·q away from the hole's loop in the image's plane, in
/// row-major order.
Patch back_project(const RangeImage& image, const cv::Mat& restored,
                   const BackProjectionOptions& options = {});

/// The colour of each patch point: `restored_color` (CV_32FC3 RGB, the size of the image the patch
/// came from) at its pixel, clamped to [0, 1].
std::vector<Rgb> patch_colors(const Patch& patch, const cv::Mat& restored_color);

}  // namespace rangefill
