// Mesh faces as CGAL triangles in an AABB tree (exact predicates, inexact constructions): shared by
// the intersection tests (core) and the surface distances of the evaluation.
#pragma once

#include <vector>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "rangefill/core/mesh.h"

namespace rangefill::cgal_triangles {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using CgalTriangle = Kernel::Triangle_3;
using Segment = Kernel::Segment_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<CgalTriangle>::const_iterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

inline Point to_point(const Vec3& p) {
  return {p.x(), p.y(), p.z()};
}

/// The triangles of `faces`, in their order.
inline std::vector<CgalTriangle> to_triangles(const Mesh& mesh, const std::vector<int>& faces) {
  std::vector<CgalTriangle> triangles;
  for (int face : faces) {
    const Triangle& t = mesh.triangles[face];
    triangles.emplace_back(to_point(mesh.positions[t[0]]), to_point(mesh.positions[t[1]]),
                           to_point(mesh.positions[t[2]]));
  }
  return triangles;
}

}  // namespace rangefill::cgal_triangles
