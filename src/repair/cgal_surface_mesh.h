// CGAL's Surface_mesh as the hole-filling code uses it (the faired patch, the CGAL baselines).
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

namespace rangefill::cgal_surface_mesh {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
using FaceIndex = SurfaceMesh::Face_index;

}  // namespace rangefill::cgal_surface_mesh
