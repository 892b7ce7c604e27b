// Complex holes (Pérez et al., Section VI-C, Figs. 10–13): a hole that no plane sees whole is
// filled in parts. A part is a run of the hole's boundary closed by a chord between its two ends;
// once it is filled, the rest of the hole (the other run and the chord) is a new, smaller hole that
// the next pass projects on a plane of its own.
#pragma once

#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"
#include "rangefill/hole/holes.h"
#include "rangefill/image/projection.h"

namespace rangefill {

/// Sub-holes of `hole` to fill first, most promising first, seen in `plane` (the hole's best plane
/// even though no plane was acceptable, ProjectionSearch::best). Each is a run of hole.vertices (in
/// loop order) of at least 3 and fewer than all vertices, closed by a chord that is no edge of the
/// mesh and that leaves into the hole at both ends, not over the surface (at each end it lies right
/// of the boundary edges there, in the planes of their faces).
///  - Where the projected boundary self-intersects (Fig. 12): the polygon is cut at an intersection
///    into two loops; the larger of those that are a single run is kept and cut again until it
///    projects as a simple polygon.
///  - Where it projects simply but parts of its rim are seen from behind: the longest run of
///    boundary edges whose rim faces face the viewer, made simple as above.
///  - Across the hole's narrowest neck: the chord of least 3-D length relative to the shorter
///    boundary arc it cuts off, so that a long thin hole, or one wrapping round a limb, is cut
///    across; both sides, larger first, then twice more the side of each part's own neck that is a
///    run. These parts need not project simply in `plane`: each gets planes of its own.
std::vector<BoundaryLoop> split_complex_hole(const Mesh& mesh, const MeshTopology& topology,
                                             const BoundaryLoop& hole, const HoleInPlane& plane);

/// A loop over `vertices` with perimeter and vector area computed, the chord included.
BoundaryLoop make_loop(const Mesh& mesh, int id, std::vector<int> vertices);

}  // namespace rangefill
