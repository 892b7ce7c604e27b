// Filling the holes of depth maps with the inpainting back-ends, in the idiom of cv::inpaint
// (conventions: depth_image.h).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rangefill/core/depth_image.h"
#include "rangefill/core/parallel.h"
#include "rangefill/inpaint/inpainters.h"
#include "rangefill/inpaint/trend.h"

namespace rangefill {

/// The back-ends' options fill_depth takes by default: InpainterOptions' own, except that foe
/// refines Telea's fill by at most 10 steps, stopping earlier when one gains less than 3e-3 of E
/// (why: docs/results.md, Depth bench).
InpainterOptions depth_inpainting_defaults();

/// DepthFillOptions::inpainter that fills along lines (fill_along_lines' rule), no back-end.
inline const char* const kAlongLines = "lines";

/// kAlongLines, then inpainter_names(): what DepthFillOptions::inpainter takes.
std::vector<std::string> depth_filler_names();

struct DepthFillOptions {
  /// Fill every hole at once along lines, without steps 1–2 below hole by hole: each pixel
  /// interpolated in inverse depth between the valid pixels it sees along its row, column and
  /// diagonals, the far surface preferred. Fast, and less accurate at depth edges
  /// (docs/depth-maps.md). Reads discontinuity, threads (bands of rows), color, max_hole_pixels
  /// and keep_border of the options below.
  bool fast = false;
  /// How each side of a hole is filled from its source (step 3 below): a name of
  /// inpainter_names(), the back-end for holes of up to backend_max_pixels, larger ones along
  /// lines; or kAlongLines for every hole along lines.
  std::string inpainter = "harmonic";
  /// The largest hole (pixels) given to the back-end; 0: every hole. The back-end's membrane
  /// hedges between surfaces where the side of a pixel is in doubt, lines commit to one; large
  /// holes (the frame's invalid border, regions with no return) cost the back-end most and are
  /// filled as well along lines. Chosen on the depth kit's tuning frames (docs/depth-maps.md).
  long long backend_max_pixels = 2000;
  /// A colour image registered to the depth (CV_8UC3, BGR or RGB; or CV_8UC1 grey), or empty.
  /// With it, a colour edge parts the sides of an occluding edge (step 2) and weakens the guesses
  /// and the smoothness (harmonic, foe) that cross it (steps 3–4); without it nothing changes.
  cv::Mat color;
  InpainterOptions inpainting = depth_inpainting_defaults();
  int threads = hardware_threads();  // holes filled at once; the result does not depend on it
  long long max_hole_pixels = 0;     // larger holes are left as they are; 0: no limit
  bool keep_border = false;          // leave holes that touch the image border as they are
  /// Depths z1 < z2 lie on different surfaces when z2 > (1 + discontinuity)·z1.
  double discontinuity = 0.05;
  /// Surface fitted to the valid pixels within `trend_ring` pixels of a hole, removed before the
  /// back-end and added back (trend.h). None by default (why: docs/results.md, Depth bench).
  TrendKind trend = TrendKind::none;
  double trend_ring = 3;
  int margin = 5;  // pixels around each hole given to the back-end (telea and ns read `radius`)
  /// With a back-end: pixels farther than this from every pixel a hole is filled from take the
  /// depth of the nearest such pixel; the back-end restores the band within. 0: no limit.
  int reach = 32;
};

/// What fill_depth did. A hole is a connected component (8-neighbourhood) of the mask.
struct DepthFillStats {
  /// Holes left as they are for one reason, and their pixels.
  struct Left {
    int holes = 0;
    long long pixels = 0;
  };
  int holes = 0;
  int filled = 0;
  long long filled_pixels = 0;
  int at_edge = 0;       // filled holes beside an occluding edge (step 1 of fill_depth)
  Left too_large;        // more than max_hole_pixels
  Left at_border;        // touch the image border, and keep_border is set
  Left without_support;  // no valid pixel borders them
  cv::Mat filled_mask;   // CV_8UC1, the depth's size: 255 at the pixels this call filled

  int left_holes() const { return too_large.holes + at_border.holes + without_support.holes; }
  long long left_pixels() const {
    return too_large.pixels + at_border.pixels + without_support.pixels;
  }
};

/// Fills the holes of a depth map, in the idiom of cv::inpaint.
///
/// `depth`: CV_16UC1 (millimetres) or CV_32FC1 (metres). `invalid_mask`: the pixels to fill,
/// CV_8UC1 of the same size, non-zero to fill (whatever their depth); empty (cv::noArray()) takes
/// every invalid pixel. `filled` receives an image of the depth's type and size: every pixel
/// outside the filled holes as given, bit for bit; 16-bit fills rounded to the millimetre. Invalid
/// pixels outside the mask are never read as data. Deterministic at any thread count. Throws
/// InvalidInput, with a one-line message, on a bad type or size, an unknown back-end or options
/// out of range (discontinuity ≤ 0, margin < 1, max_hole_pixels < 0, backend_max_pixels < 0,
/// threads < 1).
///
/// Each hole (a connected component of the mask, 8-neighbourhood) is filled on its own, from a
/// window of `margin` pixels around it. Its rim is the valid pixels 8-adjacent to it. A hole that
/// touches the image border is filled like the others (unless keep_border): the back-ends treat
/// the border as a free edge, so the fill is extrapolated from the rim inside the image, under the
/// same occlusion rule. `stats.filled_mask` tells which pixels were filled; a hole is left only
/// for a reason counted in the stats (too large, at the border when asked, no valid rim).
///  1. Occluding edges. Looking across the hole from a rim pixel p in each of the 8 directions, the
///     first valid pixel q beyond the hole lies behind p when it is deeper by more than
///     `discontinuity` and p is nearer than q's surface continued to p by as much (q's local plane:
///     inverse depth fitted to its neighbours within 2 pixels on its surface). Then p occludes: it
///     is on the near side of a depth edge the hole hides. A steep continuous surface, such as a
///     floor at a grazing angle, continues to p and makes no edge.
///  2. Sides. The background goes on behind an occluder; the occluder goes on into the hole up to
///     its silhouette continued. A hole pixel is on the near side when it sees occluding rim pixels
///     first along more than half of the 8 directions that meet the rim (inside the silhouette
///     continued) and is nearer them than the other rim pixels, through the hole, by more than 6
///     pixels; every other pixel is on the far side. Each valid pixel of the window belongs to the
///     side of its nearest rim pixel, when on that pixel's surface: each side is filled from its
///     own. So a sensor shadow (a band between a near object and the background) is filled at the
///     background's depth, never by a ramp from near to far, and a hole across a silhouette is
///     parted near it; a side with no valid pixel of its own gives its pixels to the other.
///  3. Each side is filled by the back-end (holes of up to backend_max_pixels) or along lines
///     (larger holes, or inpainter kAlongLines: fill_along_lines over the side's source pixels,
///     guesses weighted by their colour affinity to the pixel when a colour image is given). For
///     the back-end the source pixels go to inverse depth 1/z, on
///     which a plane of the scene is linear in the pixel, normalised onto [0, 1] over the source
///     (as eq. 7–8 do for range images), minus the trend if any; the back-end restores the side
///     with every other pixel of the window masked (given a colour image, the harmonic back-end
///     weighs each pair of neighbours by their colour affinity, and foe each clique of its experts
///     by the least affinity of its pixels to its centre, starting from the guided harmonic fill);
///     the fill is clamped to the source's range widened by half on either side.
///  4. Away from the edges. A hole pixel that lies between two valid pixels of one surface along
///     its row, column or a diagonal (fill_along_lines over every valid pixel of the window
///     interpolates it) and is more than 6 pixels from every occluding rim pixel, through the
///     hole, takes the lines' depth where step 3 put it on another surface: the sides' rule is
///     for pixels beside an edge, and a hole that merges with a large invalid region (the frame's
///     border, a shadow) has a rim of several surfaces that it can misassign. Holes without an
///     edge that are filled along lines skip it (step 3 was that fill).
DepthFillStats fill_depth(cv::InputArray depth, cv::InputArray invalid_mask, cv::OutputArray filled,
                          const DepthFillOptions& options = {});

}  // namespace rangefill
