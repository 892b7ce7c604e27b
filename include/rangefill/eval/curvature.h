// Discrete curvature of a triangle mesh (Meyer, Desbrun, Schröder & Barr, "Discrete
// Differential-Geometry Operators for Triangulated 2-Manifolds", 2003) and dihedral angles: what
// `rangefill bench` classifies punched regions by (Pérez et al., Section X: holes in low, medium
// and high curvature areas and on linear features).
#pragma once

#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"

namespace rangefill {

/// Per-vertex curvature from the one-ring.
struct VertexCurvature {
  std::vector<double> area;      // mixed Voronoi area A of the vertex (Meyer et al., Fig. 4)
  std::vector<double> gaussian;  // K = angle defect / A (2π − Σ angles; π − Σ on a border)
  std::vector<double> mean;      // H = |cotan Laplacian of the position| / (4A), positive where
                                 // the surface bends away from the area-weighted vertex normal
  /// The largest principal curvature in magnitude, |H| + sqrt(max(H² − K, 0)).
  double max_principal(int v) const;
};

/// Curvature of every vertex. Faces whose area is below 1e-12 of their longest edge squared add
/// nothing (no angle, cotangent or area); a vertex with no area left has zero curvature.
/// Precondition: validate_mesh passes and `topology` was built from `mesh`.
VertexCurvature vertex_curvature(const Mesh& mesh, const MeshTopology& topology);

/// Per edge of `edges.edges`, the angle between the normals of its two faces, in radians
/// (0 where the surface is flat across it, π where it folds back); 0 for an edge that does not have
/// exactly two faces or touches a degenerate face.
std::vector<double> dihedral_angles(const Mesh& mesh, const MeshEdges& edges);

}  // namespace rangefill
