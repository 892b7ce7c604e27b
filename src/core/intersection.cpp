#include "rangefill/core/intersection.h"

#include <algorithm>
#include <mutex>
#include <numeric>
#include <set>

#include "core/cgal_triangles.h"

namespace rangefill {

using namespace cgal_triangles;

struct IntersectionIndex::Tree {
  std::vector<CgalTriangle> triangles;
  std::vector<Triangle> corners;
  AabbTree tree;
  std::once_flag built;  // the tree is built on the first query, by whichever thread asks
};

IntersectionIndex::IntersectionIndex(const Mesh& mesh) : tree_(std::make_unique<Tree>()) {
  std::vector<int> all(mesh.face_count());
  std::iota(all.begin(), all.end(), 0);
  tree_->triangles = to_triangles(mesh, all);
  tree_->corners = mesh.triangles;
}

IntersectionIndex::~IntersectionIndex() = default;
IntersectionIndex::IntersectionIndex(IntersectionIndex&&) noexcept = default;
IntersectionIndex& IntersectionIndex::operator=(IntersectionIndex&&) noexcept = default;

std::vector<int> IntersectionIndex::intersecting_faces(const Vec3& a, const Vec3& b, const Vec3& c,
                                                       const Triangle& corners) const {
  std::vector<int> faces;
  if (tree_->triangles.empty()) return faces;
  std::call_once(tree_->built, [this] {
    tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
    tree_->tree.build();
  });
  std::vector<Primitive::Id> hits;
  tree_->tree.all_intersected_primitives(CgalTriangle(to_point(a), to_point(b), to_point(c)),
                                         std::back_inserter(hits));
  for (const auto& hit : hits) {
    const int face = static_cast<int>(hit - tree_->triangles.cbegin());
    const Triangle& u = tree_->corners[face];
    const bool shares = std::any_of(corners.begin(), corners.end(), [&](int v) {
      return v >= 0 && (v == u[0] || v == u[1] || v == u[2]);
    });
    if (!shares) faces.push_back(face);
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

bool triangles_intersect(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  const CgalTriangle first(to_point(a[0]), to_point(a[1]), to_point(a[2]));
  const CgalTriangle second(to_point(b[0]), to_point(b[1]), to_point(b[2]));
  if (first.is_degenerate() || second.is_degenerate()) return false;
  return CGAL::do_intersect(first, second);
}

int count_self_intersections(const Mesh& mesh, const std::vector<int>& faces) {
  const IntersectionIndex index(mesh);
  const std::set<int> queried(faces.begin(), faces.end());
  int count = 0;
  for (int face : faces) {
    const Triangle& t = mesh.triangles[face];
    for (int other : index.intersecting_faces(mesh.positions[t[0]], mesh.positions[t[1]],
                                              mesh.positions[t[2]], t)) {
      if (!(queried.count(other) && other < face)) ++count;
    }
  }
  return count;
}

}  // namespace rangefill
