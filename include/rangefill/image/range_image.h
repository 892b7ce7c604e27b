// The range image of a hole's zone (Pérez et al., Section VI): a normalised depth image on a grid
// of step q = β·d_m (eq. 6–8), the mask of the pixels to restore, and small gaps pre-interpolated
// (Section VI-B, eq. 9–10).
#pragma once

#include <array>
#include <vector>

#include <opencv2/core.hpp>

#include "rangefill/core/geometry2d.h"
#include "rangefill/core/mesh.h"
#include "rangefill/hole/holes.h"
#include "rangefill/hole/zone.h"
#include "rangefill/image/projection.h"
#include "rangefill/inpaint/pixel_labels.h"
#include "rangefill/inpaint/trend.h"

namespace rangefill {

struct RangeImageOptions {
  double beta = 0.87;                 // β of eq. 6
  int margin = 2;                     // pixels added around the zone's projection
  long long max_pixels = 16'000'000;  // larger images are refused (ProcessingError)
};

/// Everything the inverse mapping needs: pixel (row f, column k) with value r is the point
/// (x', y', z') = (x_min + k·q, y_max − f·q, r / f_esc + d_i) of the frame (eq. 13).
struct RangeImage {
  cv::Mat depth;   // CV_32F: normalised depth I'_h = (I_h − d_i)·f_esc (eq. 7); 0 where unknown
  cv::Mat labels;  // CV_8U: PixelLabel per pixel
  cv::Mat color;   // CV_32FC3: RGB interpolated like depth when the mesh has colours, else empty
  HoleInPlane plane;        // the frame and the hole's loop in it
  double step = 0;          // q
  double x_min = 0;         // frame x of column 0
  double y_max = 0;         // frame y of row 0
  double depth_offset = 0;  // d_i: min of the rasterised depth
  double depth_scale = 1;   // f_esc = 1 / (max − min) (eq. 8), or 1 / q for a flat zone

  /// CV_8U, 255 where labels == kHolePixel: the mask handed to the inpainter.
  cv::Mat mask() const;
  /// The frame-local point of pixel (row, col) with normalised depth `value` (eq. 13).
  Vec3 local_point(int row, int col, double value) const;
};

/// Rasterises the front-facing faces of the zone onto the grid (depth interpolated linearly inside
/// each triangle, the surface nearest the viewer wins), normalises depth (eq. 7–8), labels pixels
/// whose centres lie inside the projected hole boundary as hole pixels, covered ones as known,
/// uncovered ones reachable from the image border as outside and the rest as gaps. When the mesh
/// has colours they are interpolated into `color` the same way (0 where unknown). Throws
/// ProcessingError if the image would exceed options.max_pixels.
RangeImage rasterize_zone(const Mesh& mesh, const Zone& zone, const BoundaryLoop& hole,
                          const HoleInPlane& plane, double mean_edge,
                          const RangeImageOptions& options = {});

/// Share of the pixels bordering the hole mask (its 8-neighbours outside it) that hold depth from
/// the zone: how much of the hole's surroundings the image actually sees. 1 for an empty mask.
/// Pixels whose centres lie within 1.5 pixels of one of the `chords` (segments in the frame's
/// x, y) are not counted: a chord closing a part of a complex hole (Section VI-C) has the rest of
/// the hole beyond it, never surface.
double rim_support(const RangeImage& image, const std::vector<std::array<Vec2, 2>>& chords = {});

struct GapFillStats {
  int areas = 0;           // gap areas filled
  int pixels = 0;          // pixels filled
  int joined_to_hole = 0;  // gap pixels with no known neighbour at all, given to the hole mask
};

/// Section VI-B: fills every gap area, smallest first (ties: first pixel in row-major order), by
/// inward diffusion: the pixel with the most filled 8-neighbours first (eq. 9; ties by row, then
/// column) takes their mean (eq. 10). Filled gap pixels become known. A gap area that touches no
/// known pixel becomes part of the hole. Then every outside pixel takes the value of its nearest
/// known pixel, so that back-ends which read every unmasked pixel see no artificial step. The
/// colour image, if any, is filled alongside, pixel for pixel in the same way.
GapFillStats fill_small_gaps(RangeImage& image);

/// fit_trend (trend.h) of the image's depth over its labels, heights in pixels: 1 /
/// (depth_scale · step) pixels per unit of normalised depth.
Trend fit_trend(const RangeImage& image, TrendKind kind, double ring = 6);

}  // namespace rangefill
