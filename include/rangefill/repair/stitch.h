// Triangulating a hole's new points and stitching them to its boundary (Pérez et al., Section
// VIII).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"
#include "rangefill/repair/back_projection.h"
#include "rangefill/repair/fill.h"
#include "rangefill/repair/holes.h"
#include "rangefill/repair/projection.h"

namespace rangefill {

/// T1 (eq. 14–15): the patch points joined along their 8-neighbour pixel grid. Every 2×2 block of
/// present pixels gives two triangles split by the same diagonal (lower-left to upper-right), a
/// block with three present pixels gives one; all counter-clockwise seen from the frame's viewer.
/// Triangles index `patch.points`.
std::vector<Triangle> triangulate_grid(const Patch& patch);

/// Why `fill` would not join the mesh as a manifold, or nullopt when it would: each boundary edge
/// used exactly once, reversed; every other edge used twice in opposite directions; no chord
/// between boundary vertices that the mesh already has as an edge; no triangle of zero area, nor,
/// given a frame, one seen from behind.
std::optional<std::string> fill_defect(const Mesh& mesh, const MeshTopology& topology,
                                       const Fill& fill, const Frame* frame = nullptr);

/// T2 and the union: drops grid triangles that cross or touch the projected hole boundary, then
/// triangulates the band between the boundary and the grid's border by a constrained Delaunay
/// triangulation in the projection plane (2.5D, CGAL) that keeps every boundary edge and every
/// border edge, and returns T1 ∪ T2 with unused points removed (and their colours, if the patch has
/// any), checked by fill_defect with the frame; refused (not_manifold) where that fails or the
/// triangulation cannot be made.
FillOutcome stitch(const Mesh& mesh, const MeshTopology& topology, const BoundaryLoop& hole,
                   const Frame& frame, const Patch& patch, const std::vector<Triangle>& grid);

}  // namespace rangefill
