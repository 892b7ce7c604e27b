// The paper's image pipeline as a filler (Pérez et al., Sections VI–VIII): the hole's zone seen
// from a projection plane becomes a range image, the back-end restores its hole pixels (the trend
// removed first, trend.h), and the restored pixels go back to 3D and are stitched to the loop.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "rangefill/hole/filler.h"
#include "rangefill/image/back_projection.h"
#include "rangefill/image/projection.h"
#include "rangefill/image/range_image.h"
#include "rangefill/inpaint/inpainters.h"
#include "rangefill/inpaint/trend.h"

namespace rangefill {

/// Everything a person needs to look at one hole's images (HoleContext::on_images).
struct HoleImages {
  int id = 0;  // HoleReport::id
  const RangeImage& image;
  const cv::Mat& restored;
};

struct PlaneFillerOptions {
  std::string inpainter = "foe";  // the back-end (inpainter.h); "plane:BACKEND" names its own
  InpainterOptions inpainting;
  /// Trend removed before inpainting and added back (trend.h); the back-end then only restores the
  /// residual. OpenCV's telea and ns are weighted means at heart and, on curved surfaces, pull a
  /// fill towards the lower ring around the hole (below the cutting plane of a spherical cap);
  /// a quadric continued from the rim overshoots a wide spherical cap. Automatic by
  /// default: the sphere where it fits the rim better, else the quadric. `none` is the paper's
  /// pipeline, for ablations.
  TrendKind trend = TrendKind::automatic;
  double trend_ring = 3;         // known pixels within this many pixels of the hole are fitted
  double min_rim_support = 0.9;  // a plane whose image sees less of the hole's surroundings
                                 // (rim_support after gap filling) gives way to the next
  ProjectionOptions projection;
  RangeImageOptions image;
  BackProjectionOptions back_projection;
};

/// Sections VI–VIII on each acceptable plane in turn, best first, until `accept` takes a fill;
/// refused no_plane when no plane is acceptable (a complex hole), else with the first plane's
/// refusal. `name`: "plane", or "plane:BACKEND" for a back-end of its own.
std::shared_ptr<const Filler> make_plane_filler(const std::string& name,
                                                const PlaneFillerOptions& options);

/// Section VI-C: the first part of a complex hole that fills, through the planes of that part and
/// its own zone; the rest of the loop is left for the next pass. Named "plane-in-part".
std::shared_ptr<const Filler> make_plane_in_part_filler(const PlaneFillerOptions& options);

}  // namespace rangefill
