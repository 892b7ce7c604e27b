#include "rangefill/fillers/loop_patch.h"

#include <cmath>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "rangefill/core/intersection.h"
#include "rangefill/core/topology.h"
#include "rangefill/eval/metrics.h"
#include "rangefill/hole/holes.h"
#include "support.h"

namespace rangefill {
namespace {

// A regular polygon of n corners in a tilted plane, counter-clockwise about `normal`.
std::vector<Vec3> regular_polygon(int n, const Vec3& normal) {
  const Vec3 u = normal.unitOrthogonal(), v = normal.cross(u);
  std::vector<Vec3> loop;
  for (int k = 0; k < n; ++k) {
    const double angle = 2 * M_PI * k / n;
    loop.push_back(Vec3(1, 2, 3) + 2 * std::cos(angle) * u + 2 * std::sin(angle) * v);
  }
  return loop;
}

// Checks that `triangles` close `loop` as a hole fill: each loop edge (k, k+1) used once as
// (k+1, k), every other edge once in each direction; returns the total area.
double expect_closes_loop(const std::vector<Vec3>& loop, const std::vector<Triangle>& triangles) {
  const int n = static_cast<int>(loop.size());
  std::map<std::pair<int, int>, int> directed;
  double area = 0;
  for (const Triangle& t : triangles) {
    area += 0.5 * (loop[t[1]] - loop[t[0]]).cross(loop[t[2]] - loop[t[0]]).norm();
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << edge.first << "->" << edge.second;
    const bool loop_edge_reversed = (edge.second + 1) % n == edge.first;
    const bool loop_edge_forward = (edge.first + 1) % n == edge.second;
    EXPECT_FALSE(loop_edge_forward) << edge.first << "->" << edge.second;
    if (!loop_edge_reversed) {
      EXPECT_TRUE(directed.count({edge.second, edge.first}))
          << "chord " << edge.first << "-" << edge.second << " used once";
    }
  }
  for (int k = 0; k < n; ++k) EXPECT_TRUE(directed.count({(k + 1) % n, k})) << "edge " << k;
  return area;
}

// A planar convex polygon: n − 2 triangles, covering exactly its area, each loop edge used
// reversed, so every triangle faces against the loop's own orientation.
TEST(TriangulateLoopLeastArea, ConvexPolygonIsCoveredOnce) {
  const Vec3 normal = Vec3(1, -2, 2).normalized();
  for (int n : {3, 4, 7, 12}) {
    const std::vector<Vec3> loop = regular_polygon(n, normal);
    const std::vector<Triangle> triangles = triangulate_loop_least_area(loop);
    ASSERT_EQ(triangles.size(), static_cast<size_t>(n - 2)) << n;
    const double area = expect_closes_loop(loop, triangles);
    EXPECT_NEAR(area, 0.5 * n * 4 * std::sin(2 * M_PI / n), 1e-12) << n;
    for (const Triangle& t : triangles) {
      EXPECT_LT((loop[t[1]] - loop[t[0]]).cross(loop[t[2]] - loop[t[0]]).dot(normal), 0);
    }
  }
}

// Least area: a quadrilateral (0,0,0), (1,0,0), (1,1,1), (0,1,0) folded along either diagonal is
// split along 1–3 (areas 1/2 + √3/2 = 1.366) rather than 0–2 (√2/2 + √2/2 = 1.414).
TEST(TriangulateLoopLeastArea, ChoosesTheLeastArea) {
  const std::vector<Vec3> loop = {{0, 0, 0}, {1, 0, 0}, {1, 1, 1}, {0, 1, 0}};
  const std::vector<Triangle> triangles = triangulate_loop_least_area(loop);
  ASSERT_EQ(triangles.size(), 2u);
  EXPECT_NEAR(expect_closes_loop(loop, triangles), 0.5 + std::sqrt(3.0) / 2, 1e-12);
  for (const Triangle& t : triangles) {
    EXPECT_TRUE(std::count(t.begin(), t.end(), 1) && std::count(t.begin(), t.end(), 3));
  }
}

// A forbidden chord is never used, even where it would give the least area; when every
// triangulation needs a forbidden chord the result is empty; fewer than 3 points give nothing.
TEST(TriangulateLoopLeastArea, AvoidsForbiddenChords) {
  const std::vector<Vec3> quad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 1}, {0, 1, 0}};
  const std::vector<Triangle> other = triangulate_loop_least_area(quad, {{1, 3}});
  ASSERT_EQ(other.size(), 2u);
  EXPECT_NEAR(expect_closes_loop(quad, other), std::sqrt(2.0), 1e-12);
  for (const Triangle& t : other) {
    EXPECT_TRUE(std::count(t.begin(), t.end(), 0) && std::count(t.begin(), t.end(), 2));
  }
  EXPECT_TRUE(triangulate_loop_least_area(quad, {{0, 2}, {1, 3}}).empty());

  const std::vector<Vec3> octagon = regular_polygon(8, Vec3::UnitZ());
  const std::set<std::pair<int, int>> forbidden = {{0, 4}, {2, 6}, {1, 5}, {0, 2}, {4, 6}};
  const std::vector<Triangle> triangles = triangulate_loop_least_area(octagon, forbidden);
  ASSERT_EQ(triangles.size(), 6u);
  expect_closes_loop(octagon, triangles);
  for (const Triangle& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::pair<int, int> chord = std::minmax(t[k], t[(k + 1) % 3]);
      EXPECT_FALSE(forbidden.count(chord)) << chord.first << "-" << chord.second;
    }
  }
  EXPECT_TRUE(triangulate_loop_least_area({{0, 0, 0}, {1, 0, 0}}).empty());
  EXPECT_EQ(triangulate_loop_least_area({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}),
            (std::vector<Triangle>{{2, 1, 0}}));
}

// Liepa's triangulation of each loop, from any starting vertex, closes the sphere with b − 2
// triangles oriented like the surface (each loop edge reversed) and without self-intersection.
TEST(TriangulateLoopLiepa, ClosesEachLoopOrientedLikeTheSurface) {
  const Mesh mesh = testing::remove_faces(testing::make_sphere(16), [](const Vec3& p) {
    return (p - Vec3(0, 0, 1)).norm() < 0.3 || (p - Vec3(0, 0, -1)).norm() < 0.3;
  });
  const MeshTopology topology = build_topology(mesh);
  Mesh closed = mesh;
  for (const BoundaryLoop& loop : find_holes(mesh, topology).loops) {
    const int n = static_cast<int>(loop.vertices.size());
    const int start = loop.id == 0 ? 0 : n / 2;  // the second loop from elsewhere on it
    std::vector<int> vertices;
    std::vector<Vec3> points, third_points;
    for (int k = 0; k < n; ++k) {
      const int a = loop.vertices[(start + k) % n], b = loop.vertices[(start + k + 1) % n];
      vertices.push_back(a);
      points.push_back(mesh.positions[a]);
      const int along = find_halfedge(mesh, topology, a, b);
      third_points.push_back(
          mesh.positions[mesh.triangles[halfedge_face(along)][prev_halfedge(along) % 3]]);
    }
    const std::vector<Triangle> patch = triangulate_loop_liepa(points, third_points);
    EXPECT_EQ(static_cast<int>(patch.size()), n - 2) << "loop " << loop.id;
    for (const Triangle& t : patch) {
      add_face(closed, {vertices[t[0]], vertices[t[1]], vertices[t[2]]}, loop.id);
    }
  }
  EXPECT_TRUE(check_manifold(closed).closed_manifold());
  EXPECT_EQ(count_self_intersections(closed, faces_of_hole(closed, kAnyHole)), 0);
  EXPECT_THROW(triangulate_loop_liepa({Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()}, {}),
               InvalidInput);
}

}  // namespace
}  // namespace rangefill
