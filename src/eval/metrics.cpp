#include "rangefill/eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/cgal_triangles.h"
#include "rangefill/core/errors.h"
#include "rangefill/core/topology.h"
#include "rangefill/hole/holes.h"

namespace rangefill {

namespace {

using namespace cgal_triangles;

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
  distance.mean = 0.5 * (first_sum / static_cast<double>(first_samples.size()) +
                         second_sum / static_cast<double>(second_samples.size()));
  return distance;
}

std::vector<double> distances_to_faces(const std::vector<Vec3>& points, const Mesh& mesh,
                                       const std::vector<int>& faces) {
  if (faces.empty()) throw InvalidInput("distances to faces: no face");
  const std::vector<CgalTriangle> triangles = to_triangles(mesh, faces);
  AabbTree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  std::vector<double> distances;
  distances.reserve(points.size());
  for (const Vec3& p : points) distances.push_back(std::sqrt(tree.squared_distance(to_point(p))));
  return distances;
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

double smallest_angle_degrees(const Mesh& mesh, const std::vector<int>& faces) {
  double smallest = M_PI;
  for (int face : faces) {
    const Triangle& t = mesh.triangles[face];
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.positions[t[k]];
      const Vec3 u = mesh.positions[t[(k + 1) % 3]] - p, v = mesh.positions[t[(k + 2) % 3]] - p;
      smallest = std::min(smallest, std::atan2(u.cross(v).norm(), u.dot(v)));
    }
  }
  return smallest * 180 / M_PI;
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
