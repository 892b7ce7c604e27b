// Intersection tests of triangles against a mesh: what refuses a fill that would cut through the
// surface, and counts the self-intersections of a mesh. Exact predicates (CGAL).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "rangefill/core/mesh.h"

namespace rangefill {

/// The faces of a mesh in uniform grids for intersection queries, so that a query costs what the
/// faces near it do. The grids are built on the first query; queries may run from several threads.
/// The index reads `mesh`, which must outlive it and keep its faces and their positions while it
/// is queried.
class IntersectionIndex {
 public:
  /// Every face indexed: O(F) to build.
  explicit IntersectionIndex(const Mesh& mesh);
  /// Only the faces near `regions` (boxes, low and high corners) indexed: building reads each
  /// face's box once and grids those near the regions, so that it costs little more than a pass
  /// over the mesh when the regions are small; a query whose box lies outside them reads every
  /// face.
  IntersectionIndex(const Mesh& mesh, std::vector<std::array<Vec3, 2>> regions);
  ~IntersectionIndex();
  IntersectionIndex(IntersectionIndex&&) noexcept;
  IntersectionIndex& operator=(IntersectionIndex&&) noexcept;

  /// Faces that intersect the triangle (a, b, c) other than where they share vertices with
  /// `corners` (mesh vertex ids of the triangle's corners, or vertices at the same point; -1 for a
  /// corner not in the mesh), as
  /// CGAL's self_intersections decides: a face sharing one vertex intersects when an edge of one
  /// opposite that vertex crosses the other; sharing an edge, when the two are coplanar and folded
  /// onto each other; sharing all three, always. A degenerate triangle meets nothing.
  std::vector<int> intersecting_faces(const Vec3& a, const Vec3& b, const Vec3& c,
                                      const Triangle& corners) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

/// Whether two triangles intersect beyond the vertices they share, as
/// IntersectionIndex::intersecting_faces decides; `ids_a`, `ids_b` name their corners (-1: a
/// corner no other triangle has). Two named corners at the same point are shared, as a welded
/// mesh would share them (a surface that touches itself there). Degenerate triangles meet nothing.
bool triangles_intersect(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b,
                         const Triangle& ids_a = {-1, -1, -1},
                         const Triangle& ids_b = {-1, -1, -1});

/// Pairs (f, g) with f in `faces` and g any other face of the mesh that intersect beyond their
/// shared vertices (IntersectionIndex::intersecting_faces). Each unordered pair is counted once.
int count_self_intersections(const Mesh& mesh, const std::vector<int>& faces);

}  // namespace rangefill
