// Measuring a repair: distances between surfaces, closedness, self-intersections, edge ratio.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "rangefill/mesh.h"

namespace rangefill {

/// Distances between two triangle sets, each given as a mesh and the faces to use.
struct SurfaceDistance {
  double hausdorff = 0;    // max of the two one-sided distances
  double from_first = 0;   // max over points of the first set of the distance to the second
  double from_second = 0;  // max over points of the second set of the distance to the first
  double mean = 0;         // mean over the samples of both sets of the distance to the other
};

/// Samples both sets (vertices and a barycentric grid no coarser than `spacing` on every triangle)
/// and measures exact point-to-triangle distances to the other set (CGAL AABB tree). Throws
/// InvalidInput if a set is empty or spacing is not positive.
SurfaceDistance surface_distance(const Mesh& first, const std::vector<int>& first_faces,
                                 const Mesh& second, const std::vector<int>& second_faces,
                                 double spacing);

/// Whether a mesh is a closed, consistently oriented 2-manifold, and why not.
struct ManifoldCheck {
  int boundary_loops = 0;
  int nonmanifold_edges = 0;
  int misoriented_edges = 0;
  int nonmanifold_vertices = 0;
  bool closed_manifold() const {
    return boundary_loops == 0 && nonmanifold_edges == 0 && misoriented_edges == 0 &&
           nonmanifold_vertices == 0;
  }
};
ManifoldCheck check_manifold(const Mesh& mesh);

/// The faces of a mesh in a bounding-volume tree (CGAL AABB tree) for intersection queries. The
/// tree is built in O(F log F) on the first query; queries may run from several threads.
class IntersectionIndex {
 public:
  explicit IntersectionIndex(const Mesh& mesh);
  ~IntersectionIndex();
  IntersectionIndex(IntersectionIndex&&) noexcept;
  IntersectionIndex& operator=(IntersectionIndex&&) noexcept;

  /// Faces that intersect the triangle (a, b, c), leaving out those that share a vertex with
  /// `corners` (mesh vertex ids of the triangle's corners; -1 for a corner not in the mesh).
  std::vector<int> intersecting_faces(const Vec3& a, const Vec3& b, const Vec3& c,
                                      const Triangle& corners) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

/// Whether two triangles share a point (exact predicates, CGAL). Degenerate triangles meet nothing.
bool triangles_intersect(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b);

/// Pairs (f, g) with f in `faces` and g any face of the mesh, not sharing a vertex, whose triangles
/// intersect. Each unordered pair is counted once.
int count_self_intersections(const Mesh& mesh, const std::vector<int>& faces);

/// Mean length of the unique edges of `faces` (the edge ratio r of Table 8 divides it by d_m).
double mean_edge_length(const Mesh& mesh, const std::vector<int>& faces);

/// The faces whose provenance is `hole` (or every generated face for kAnyHole).
inline constexpr int kAnyHole = -2;
std::vector<int> faces_of_hole(const Mesh& mesh, int hole);

}  // namespace rangefill
