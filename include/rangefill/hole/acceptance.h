// The pipeline's step after every filler: a fill's triangles given larger angles (patch_angles.h),
// then the fill refused unless it joins the mesh as a manifold without cutting the surface or
// itself. Fillers do not check their own fills; they hand them to this step (filler.h).
#pragma once

#include "rangefill/hole/fill.h"
#include "rangefill/hole/filler.h"

namespace rangefill {

struct AcceptanceOptions {
  /// The angle pass before the checks. Off in band tests (selection.h): they score a fill's shape,
  /// which the pass, reshaping triangles over the same surface, leaves alone.
  bool larger_angles = true;
};

/// `fill` (of a loop of `surface`) as it joins the mesh, or refused: not_manifold with the defect
/// (fill_defect, fill.h), intersects when a fill triangle meets a face of the surface or a
/// non-adjacent fill triangle (exact predicates, core/intersection.h).
FillOutcome accept_fill(const SurfaceContext& surface, Fill fill,
                        const AcceptanceOptions& options = {});

}  // namespace rangefill
