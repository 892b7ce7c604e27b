// Hole detection (Pérez et al., Section IV, eq. 1): every closed loop of boundary edges.
#pragma once

#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"

namespace rangefill {

/// One closed loop of boundary edges B_ρ = {<v1,v2>, ..., <vp,v1>} (eq. 1).
///
/// `vertices` follow the orientation of the faces on the loop: each consecutive pair (v_k, v_k+1)
/// is a half-edge of a mesh face, so the surface lies on the left of the loop and a triangle that
/// fills the hole uses the pair as (v_k+1, v_k). A loop may pass a non-manifold vertex twice.
struct BoundaryLoop {
  int id = 0;                 // index in HoleSet::loops, stable for the same mesh
  std::vector<int> vertices;  // ordered, first vertex not repeated at the end
  double perimeter = 0;       // sum of edge lengths
  double area = 0;            // |vector area| = |½ Σ p_k × p_k+1|: exact for a planar loop
  int component = 0;          // component of the faces bordering it
  double area_share = 0;      // `area` over the area of the faces of its component
};

/// The loop's vertices in ascending order: the same loop gives the same key wherever it starts.
std::vector<int> sorted_vertices(const BoundaryLoop& loop);

/// Default of RepairOptions::border_share: a loop whose fill would cover at least a fifth of its
/// component's surface bounds an open surface (the figures behind it: docs/results.md, Border or
/// hole).
inline constexpr double kBorderShare = 0.2;

/// True when `loop` is taken for the border of an open surface (a single-view scan, a cut part)
/// rather than a hole: its area_share is at least `border_share` (> 0; 0 makes no loop a border).
bool is_border(const BoundaryLoop& loop, double border_share = kBorderShare);

struct HoleSet {
  std::vector<BoundaryLoop> loops;  // ordered by their first boundary half-edge
  // Vertices on more than two boundary edges (loops touch there), in ascending order.
  std::vector<int> pinched_vertices;
  // Boundary edges that do not close into a loop (only next to non-manifold or misoriented edges).
  int open_boundary_edges = 0;
  std::vector<double> component_areas;  // the area of each component's faces (face_components)
};

/// Traces every boundary loop in O(boundary edges) once the topology exists. Where loops touch at a
/// vertex, each continues into the angular gap on its right (about the vertex normal) and stays in
/// its own component, so touching loops are kept apart. Edges shared by more than two faces are not
/// boundary edges and are left to MeshTopology's counts.
HoleSet find_holes(const Mesh& mesh, const MeshTopology& topology);

}  // namespace rangefill
