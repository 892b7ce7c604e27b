// The classes of an image's pixels as the trend (trend.h), the range image of a hole
// (image/range_image.h) and depth filling (depth/fill_depth.h) label them.
#pragma once

#include <cstdint>

namespace rangefill {

/// A pixel's class, in a CV_8U labels image.
enum PixelLabel : std::uint8_t {
  kKnownPixel = 0,    // a measured value (in a range image: depth rasterised from the zone)
  kHolePixel = 1,     // to be restored by the inpainter (the mask)
  kGapPixel = 2,      // in a range image, inside the zone but not covered: filled by
                      // fill_small_gaps (Pérez et al., Section VI-B)
  kOutsidePixel = 3,  // outside the region of interest (a range image's λ_o): holds the nearest
                      // value, no surface
};

}  // namespace rangefill
