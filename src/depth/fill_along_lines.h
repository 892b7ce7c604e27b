// fill_depth's fast mode (DepthFillOptions::fast): each pixel interpolated between the valid
// pixels it sees along 4 lines, under the occlusion rule of fill_depth.
#pragma once

#include <opencv2/core.hpp>

namespace rangefill {

/// How much farther (pixels) than the nearest surface a surface may be seen from a pixel and still
/// be the one the pixel takes, the far one being preferred (the background goes on behind an
/// occluder): beyond it, across a large invalid region, a line sees surfaces that are not the
/// pixel's. Chosen on the depth kit's tuning frames (docs/depth-maps.md).
constexpr float kFarSurfaceMargin = 4;

/// Fills the pixels of `to_fill` (CV_8UC1, non-zero to fill) from the pixels of `data` (CV_8UC1)
/// of `z` (CV_32FC1, metres). Returns CV_32FC1 metres at the pixels filled, 0 elsewhere: a pixel
/// is left only when no pixel of `data` lies on its row, its column or its diagonals, nor beyond
/// pixels filled in an earlier round.
///
/// Along each of the 4 lines through a pixel, the nearest data pixels on either side are its
/// ends. Two ends on one surface (same_surface with `discontinuity`) give the linear interpolation
/// between them in inverse depth, a plane of the scene being linear in the pixel there, weighted
/// by 1 / span²; otherwise each end is a constant guess weighted by 1 / distance². Interpolations
/// are preferred to constants, and among either, the far surface to the near: the weighted mean
/// of those within `discontinuity` of the farthest (the background goes on behind an occluder, as
/// in fill_depth's step 2), among those that come from no more than 4 pixels beyond the nearest
/// (a surface seen far away along one line, across a large invalid region, does not override the
/// near one).
/// With `color` (CV_32FC3, guide_color), each guess's weight is multiplied by the colour affinity
/// of the pixel to the ends it comes from (color_guide.h), as a joint-bilateral filter weighs.
/// O(pixels), no window per hole. Pixels left after a round are filled in the next from those
/// filled, until none is left or a round fills none. `interpolated`, when given, receives CV_8UC1
/// with 255 at the pixels filled by interpolations (some line's two ends on one surface).
cv::Mat fill_along_lines(const cv::Mat& z, const cv::Mat& data, const cv::Mat& to_fill,
                         double discontinuity, int threads, const cv::Mat& color = {},
                         cv::Mat* interpolated = nullptr);

}  // namespace rangefill
