#include "rangefill/metrics.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numeric>
#include <set>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "rangefill/errors.h"
#include "rangefill/holes.h"
#include "rangefill/topology.h"

namespace rangefill {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using CgalTriangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<CgalTriangle>::const_iterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Point to_point(const Vec3& p) {
  return {p.x(), p.y(), p.z()};
}

std::vector<CgalTriangle> to_triangles(const Mesh& mesh, const std::vector<int>& faces) {
  std::vector<CgalTriangle> triangles;
  for (int face : faces) {
    const Triangle& t = mesh.triangles[face];
    triangles.emplace_back(to_point(mesh.positions[t[0]]), to_point(mesh.positions[t[1]]),
                           to_point(mesh.positions[t[2]]));
  }
  return triangles;
}

// Every vertex and a barycentric grid of step at most `spacing` on each face.
std::vector<Point> sample(const Mesh& mesh, const std::vector<int>& faces, double spacing) {
  std::vector<Point> samples;
  for (int face : faces) {
    const Triangle& t = mesh.triangles[face];
    const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int n = std::max(1, static_cast<int>(std::ceil(longest / spacing)));
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        samples.push_back(to_point(a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n)));
      }
    }
  }
  return samples;
}

// Max and sum of the distances from `samples` to the triangles of `tree`.
std::pair<double, double> distances_to(const std::vector<Point>& samples, const AabbTree& tree) {
  double largest = 0, sum = 0;
  for (const Point& p : samples) {
    const double d = std::sqrt(tree.squared_distance(p));
    largest = std::max(largest, d);
    sum += d;
  }
  return {largest, sum};
}

}  // namespace

SurfaceDistance surface_distance(const Mesh& first, const std::vector<int>& first_faces,
                                 const Mesh& second, const std::vector<int>& second_faces,
                                 double spacing) {
  if (first_faces.empty() || second_faces.empty()) {
    throw InvalidInput("surface distance: a face set is empty");
  }
  if (!(spacing > 0)) throw InvalidInput("surface distance: spacing must be positive");
  const std::vector<CgalTriangle> first_triangles = to_triangles(first, first_faces);
  const std::vector<CgalTriangle> second_triangles = to_triangles(second, second_faces);
  AabbTree first_tree(first_triangles.begin(), first_triangles.end());
  AabbTree second_tree(second_triangles.begin(), second_triangles.end());
  first_tree.accelerate_distance_queries();
  second_tree.accelerate_distance_queries();
  const std::vector<Point> first_samples = sample(first, first_faces, spacing);
  const std::vector<Point> second_samples = sample(second, second_faces, spacing);
  const auto [from_first, first_sum] = distances_to(first_samples, second_tree);
  const auto [from_second, second_sum] = distances_to(second_samples, first_tree);
  SurfaceDistance distance;
  distance.from_first = from_first;
  distance.from_second = from_second;
  distance.hausdorff = std::max(from_first, from_second);
  distance.mean =
      (first_sum + second_sum) / static_cast<double>(first_samples.size() + second_samples.size());
  return distance;
}

ManifoldCheck check_manifold(const Mesh& mesh) {
  const MeshTopology topology = build_topology(mesh);
  ManifoldCheck check;
  check.boundary_loops = static_cast<int>(find_holes(mesh, topology).loops.size());
  check.nonmanifold_edges = topology.nonmanifold_edge_count;
  check.misoriented_edges = topology.misoriented_edge_count;
  check.nonmanifold_vertices = static_cast<int>(topology.nonmanifold_vertices.size());
  return check;
}

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

double mean_edge_length(const Mesh& mesh, const std::vector<int>& faces) {
  std::set<std::pair<int, int>> edges;
  for (int face : faces) {
    const Triangle& t = mesh.triangles[face];
    for (int k = 0; k < 3; ++k) edges.emplace(std::minmax(t[k], t[(k + 1) % 3]));
  }
  double sum = 0;
  for (const auto& [a, b] : edges) sum += (mesh.positions[a] - mesh.positions[b]).norm();
  return edges.empty() ? 0.0 : sum / static_cast<double>(edges.size());
}

std::vector<int> faces_of_hole(const Mesh& mesh, int hole) {
  std::vector<int> faces;
  for (int f = 0; f < mesh.face_count(); ++f) {
    if (hole == kAnyHole ? mesh.face_hole[f] != kOriginal : mesh.face_hole[f] == hole)
      faces.push_back(f);
  }
  return faces;
}

}  // namespace rangefill
