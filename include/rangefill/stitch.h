// Triangulating a hole's new points and stitching them to its boundary (Pérez et al., Section
// VIII).
#pragma once

#include <vector>

#include "rangefill/back_projection.h"
#include "rangefill/holes.h"
#include "rangefill/mesh.h"
#include "rangefill/projection.h"
#include "rangefill/topology.h"

namespace rangefill {

/// T1 (eq. 14–15): the patch points joined along their 8-neighbour pixel grid. Every 2×2 block of
/// present pixels gives two triangles split by the same diagonal (lower-left to upper-right), a
/// block with three present pixels gives one; all counter-clockwise seen from the frame's viewer.
/// Triangles index `patch.points`.
std::vector<Triangle> triangulate_grid(const Patch& patch);

/// A hole's fill before it joins the mesh. Fill vertex i < boundary.size() is mesh vertex
/// boundary[i]; fill vertex boundary.size() + k is the new point points[k].
struct Fill {
  std::vector<int> boundary;
  std::vector<Vec3> points;
  std::vector<Triangle> triangles;
};

/// T2 and the union: drops grid triangles that cross or touch the projected hole boundary, then
/// triangulates the band between the boundary and the grid's border by a constrained Delaunay
/// triangulation in the projection plane (2.5D, CGAL) that keeps every boundary edge and every
/// border edge, and returns T1 ∪ T2 with unused points removed. Throws ProcessingError (naming the
/// hole) when the result would not join the mesh as a manifold: a boundary edge not used exactly
/// once in the right direction, an edge used twice in one direction, a chord between boundary
/// vertices that the mesh already has as an edge, or a triangle that is degenerate or seen from
/// behind.
Fill stitch(const Mesh& mesh, const MeshTopology& topology, const BoundaryLoop& hole,
            const Frame& frame, const Patch& patch, const std::vector<Triangle>& grid);

}  // namespace rangefill
