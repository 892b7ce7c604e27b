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

namespace {

// Whether triangles t (query) and u (a face), which meet and share the vertices marked in
// shared_t / shared_u, intersect elsewhere, as CGAL's self_intersections decides: sharing one
// vertex, an edge opposite it crosses the other triangle; sharing an edge, they are coplanar and
// folded onto each other; sharing all three, they are the same face.
bool meet_beyond_shared(const std::array<Point, 3>& t, const std::array<Point, 3>& u,
                        const std::array<bool, 3>& shared_t, const std::array<bool, 3>& shared_u) {
  const int count = static_cast<int>(std::count(shared_t.begin(), shared_t.end(), true));
  if (count == 0 || count == 3) return true;
  const auto index_of = [](const std::array<bool, 3>& marks, bool value) {
    return static_cast<int>(std::find(marks.begin(), marks.end(), value) - marks.begin());
  };
  if (count == 1) {
    const int i = index_of(shared_t, true), j = index_of(shared_u, true);
    const CgalTriangle triangle_t(t[0], t[1], t[2]), triangle_u(u[0], u[1], u[2]);
    return CGAL::do_intersect(Segment(t[(i + 1) % 3], t[(i + 2) % 3]), triangle_u) ||
           CGAL::do_intersect(Segment(u[(j + 1) % 3], u[(j + 2) % 3]), triangle_t);
  }
  const int i = index_of(shared_t, false), j = index_of(shared_u, false);
  const Point &p = t[(i + 1) % 3], &q = t[(i + 2) % 3];
  return CGAL::coplanar(p, q, t[i], u[j]) &&
         CGAL::coplanar_orientation(p, q, t[i], u[j]) == CGAL::POSITIVE;
}

// Which corners of t and of u are the same vertex (ids; -1 is no vertex).
std::pair<std::array<bool, 3>, std::array<bool, 3>> shared_corners(const Triangle& t,
                                                                   const Triangle& u) {
  std::array<bool, 3> shared_t{}, shared_u{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (t[i] >= 0 && t[i] == u[j]) shared_t[i] = shared_u[j] = true;
    }
  }
  return {shared_t, shared_u};
}

}  // namespace

std::vector<int> IntersectionIndex::intersecting_faces(const Vec3& a, const Vec3& b, const Vec3& c,
                                                       const Triangle& corners) const {
  std::vector<int> faces;
  if (tree_->triangles.empty()) return faces;
  std::call_once(tree_->built, [this] {
    tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
    tree_->tree.build();
  });
  const std::array<Point, 3> query = {to_point(a), to_point(b), to_point(c)};
  const CgalTriangle triangle(query[0], query[1], query[2]);
  if (triangle.is_degenerate()) return faces;
  std::vector<Primitive::Id> hits;
  tree_->tree.all_intersected_primitives(triangle, std::back_inserter(hits));
  for (const auto& hit : hits) {
    const int face = static_cast<int>(hit - tree_->triangles.cbegin());
    const Triangle& u = tree_->corners[face];
    const auto [shared_query, shared_face] = shared_corners(corners, u);
    const CgalTriangle& other = *hit;
    if (other.is_degenerate()) continue;
    if (meet_beyond_shared(query, {other[0], other[1], other[2]}, shared_query, shared_face)) {
      faces.push_back(face);
    }
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

bool triangles_intersect(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b,
                         const Triangle& ids_a, const Triangle& ids_b) {
  const std::array<Point, 3> first = {to_point(a[0]), to_point(a[1]), to_point(a[2])};
  const std::array<Point, 3> second = {to_point(b[0]), to_point(b[1]), to_point(b[2])};
  const CgalTriangle triangle_a(first[0], first[1], first[2]);
  const CgalTriangle triangle_b(second[0], second[1], second[2]);
  if (triangle_a.is_degenerate() || triangle_b.is_degenerate()) return false;
  if (!CGAL::do_intersect(triangle_a, triangle_b)) return false;
  const auto [shared_a, shared_b] = shared_corners(ids_a, ids_b);
  return meet_beyond_shared(first, second, shared_a, shared_b);
}

int count_self_intersections(const Mesh& mesh, const std::vector<int>& faces) {
  const IntersectionIndex index(mesh);
  const std::set<int> queried(faces.begin(), faces.end());
  int count = 0;
  for (int face : faces) {
    const Triangle& t = mesh.triangles[face];
    for (int other : index.intersecting_faces(mesh.positions[t[0]], mesh.positions[t[1]],
                                              mesh.positions[t[2]], t)) {
      if (other != face && !(queried.count(other) && other < face)) ++count;
    }
  }
  return count;
}

}  // namespace rangefill
