// Depth patches cut from meshes the way the repair pipeline sees a hole's surroundings, and holes
// punched into them: the data back-ends are trained and compared on.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rangefill/core/mesh.h"
#include "rangefill/inpaint/inpainter.h"
#include "rangefill/inpaint/trend.h"

namespace rangefill {

struct PatchOptions {
  int size = 32;       // patches are size × size pixels
  int count = 40;      // patches wanted from the mesh
  double beta = 0.87;  // grid step q = β·d_m, as in the pipeline (eq. 6)
  std::uint64_t seed = 1;
  int attempts = 20;        // random centres tried per patch wanted
  double max_unseen = 0.3;  // share of a patch's pixels that may lie off the visible surface
};

/// A patch of a range image as the pipeline makes them.
struct DepthPatch {
  cv::Mat depth;  // CV_32F, normalised by eq. 7–8 over the zone
  cv::Mat seen;   // CV_8U, 255 where the surface was rasterised; elsewhere (off the zone or behind
                  // it) depth is extended from the nearest seen pixel, as fill_small_gaps does
  double mean_edges_per_unit = 1;  // d_m in one unit of depth: 1 / (f_esc · d_m)
};

/// Depth patches of `mesh`: around a random vertex, the faces within the patch's reach are seen
/// along their area-weighted normal and rasterised with the pipeline's code (rasterize_zone,
/// fill_small_gaps; faces seen from behind are not drawn, the nearest surface wins), and the
/// central size × size pixels are kept when at most `max_unseen` of them are unseen. Deterministic
/// for a seed; may return fewer than asked.
std::vector<DepthPatch> depth_patches(const Mesh& mesh, const PatchOptions& options);

/// A random blob mask: the union of 1–4 ellipses covering between min_fraction and max_fraction
/// of the patch, kept `margin` pixels from its border. CV_8U, 255 = to restore.
cv::Mat blob_mask(cv::Size size, double min_fraction, double max_fraction, int margin,
                  std::uint64_t seed);

/// One patch with a hole, as a back-end receives it in the pipeline: the depth minus the trend
/// fitted around the hole (trend.h), the hole's pixels to be restored.
struct HoleSample {
  cv::Mat truth;  // CV_64F: the residual everywhere, the answer at the masked pixels
  cv::Mat mask;   // CV_8U: 255 at the pixels to restore
  double mean_edges_per_unit = 1;  // DepthPatch's
};

/// The sample of `patch` with `mask` (CV_8U, 255 = to restore; every masked pixel seen), the
/// trend fitted to the seen pixels like RepairOptions' defaults.
HoleSample make_hole_sample(const DepthPatch& patch, const cv::Mat& mask,
                            TrendKind trend = TrendKind::quadric, double ring = 3);

struct HoleSampleOptions {
  PatchOptions patches;
  double min_hole = 0.05, max_hole = 0.30;  // share of the patch's pixels masked
  int margin = 4;                           // masks keep this far from the patch border
};

/// The data `train-foe` fits: depth_patches of `mesh`, seeded by
/// seed_for_mesh(options.patches.seed, name) so each mesh gets its own patches, each with a
/// blob_mask (less its unseen pixels) and made a sample like make_hole_sample's defaults.
std::vector<HoleSample> hole_samples(const Mesh& mesh, const std::string& name,
                                     const HoleSampleOptions& options);

/// The root mean square error of `inpainter`'s restoration of the sample's masked pixels, in d_m.
double restoration_rmse(const HoleSample& sample, const Inpainter& inpainter);

}  // namespace rangefill
