// Patches of a hole's loop without new vertices: the last resort of the fill chain (repair.h), and
// what closes the advancing front, and the faired patch's first triangulation. Liepa's
// minimum-weight triangulation and the least-area one, both able to avoid given chords.
#pragma once

#include <set>
#include <utility>
#include <vector>

#include "rangefill/core/mesh.h"

namespace rangefill {

/// Liepa's minimum-weight triangulation of the closed polygon `loop` (3D), as CGAL's
/// triangulate_hole_polyline computes it: the largest dihedral angle first, then the area, the
/// angles across the loop's edges measured against the faces outside, whose third corners
/// `third_points` gives (one per edge (k, k + 1)). Searched among the faces of the 3D Delaunay
/// triangulation of the loop (and every triangle on a loop edge it lacks), failing that among all
/// triangles of it; no triangle uses a `forbidden` chord (pairs of positions in `loop`, smaller
/// first). Equal weights are decided by vertex order, where CGAL's search follows the addresses of
/// its Delaunay cells. Triangles index `loop` and use each edge (k, k + 1) reversed, like
/// triangulate_loop_least_area's. Empty when none. Throws InvalidInput unless there is one third
/// point per edge.
std::vector<Triangle> triangulate_loop_liepa(const std::vector<Vec3>& loop,
                                             const std::vector<Vec3>& third_points,
                                             const std::set<std::pair<int, int>>& forbidden = {});

/// The triangulation of the closed polygon `loop` (3D) of least total area (Barequet–Sharir
/// dynamic programming, O(n³); the area weight of Liepa 2003) that uses none of the `forbidden`
/// chords (pairs of positions in `loop`, smaller first). Triangles index `loop` and use each edge
/// (k, k+1) reversed, as the fill of a hole traced like `loop` does. Empty when none exists.
/// CGAL's triangulate_hole_polyline does the same without forbidden chords, which a front that
/// touches itself needs.
std::vector<Triangle> triangulate_loop_least_area(
    const std::vector<Vec3>& loop, const std::set<std::pair<int, int>>& forbidden = {});

}  // namespace rangefill
