// CGAL's Surface_mesh as the hole-filling code uses it (the faired patch, the patch's angles, the
// CGAL baselines).
#pragma once

#include <map>
#include <set>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"

namespace rangefill::cgal_surface_mesh {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
using FaceIndex = SurfaceMesh::Face_index;

/// Some faces of a mesh as a Surface_mesh, its vertices added in first use; `local` maps mesh
/// vertex ids to them, `global` back (global[v] for the part's vertex v).
struct MeshPart {
  SurfaceMesh surface;
  std::map<int, VertexIndex> local;
  std::vector<int> global;

  /// Adds the mesh's face; false when it would make the part non-manifold or misoriented.
  bool add_face(const Mesh& mesh, int face) {
    std::array<VertexIndex, 3> corners;
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles[face][k];
      auto [entry, added] = local.emplace(v, VertexIndex());
      if (added) {
        const Vec3& p = mesh.positions[v];
        entry->second = surface.add_vertex({p.x(), p.y(), p.z()});
        global.push_back(v);
      }
      corners[k] = entry->second;
    }
    return surface.add_face(corners[0], corners[1], corners[2]) != SurfaceMesh::null_face();
  }
};

}  // namespace rangefill::cgal_surface_mesh
