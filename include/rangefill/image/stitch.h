// Triangulating a hole's new points and stitching them to its boundary (Pérez et al., Section
// VIII).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"
#include "rangefill/hole/fill.h"
#include "rangefill/hole/holes.h"
#include "rangefill/image/back_projection.h"
#include "rangefill/image/projection.h"

namespace rangefill {

/// T1 (eq. 14–15): the patch points joined along their 8-neighbour pixel grid. Every 2×2 block of
/// present pixels gives two triangles split by the same diagonal (lower-left to upper-right), a
/// block with three present pixels gives one; all counter-clockwise seen from the frame's viewer.
/// Triangles index `patch.points`.
std::vector<Triangle> triangulate_grid(const Patch& patch);

/// T2 and the union: drops grid triangles that cross or touch the hole's loop in `plane`, then
/// triangulates the band between the loop and the grid's border by a constrained Delaunay
/// triangulation in the plane (2.5D, CGAL) that keeps every boundary edge and every border edge,
/// and returns T1 ∪ T2 with unused points removed (and their colours, if the patch has any),
/// checked by fill_defect (fill.h) with the frame's normal for viewer; refused (not_manifold) where
/// that fails or the triangulation cannot be made.
FillOutcome stitch(const Mesh& mesh, const MeshTopology& topology, const BoundaryLoop& hole,
                   const HoleInPlane& plane, const Patch& patch, const std::vector<Triangle>& grid);

}  // namespace rangefill
