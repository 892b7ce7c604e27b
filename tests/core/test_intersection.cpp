// Triangle intersection tests (exact predicates): pairs, the index of a mesh's faces, counts.
#include "rangefill/core/intersection.h"

#include <numeric>

#include <gtest/gtest.h>

#include "support.h"

namespace rangefill {
namespace {

// Two triangles that cross: one in z = 0, one standing in x = 0 and piercing it.
Mesh crossing_pair() {
  return make_mesh({{-1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0.2, -1}, {0, 0.2, 1}, {0, 0.5, 0.2}},
                   {{0, 1, 2}, {3, 4, 5}});
}

// The crossing pair counts once, whichever of its faces are queried; a closed cube and a closed
// sphere count none (their neighbouring faces share vertices and are left out).
TEST(CountSelfIntersections, CountsEachCrossingPairOnce) {
  const Mesh pair = crossing_pair();
  EXPECT_EQ(count_self_intersections(pair, {0, 1}), 1);
  EXPECT_EQ(count_self_intersections(pair, {0}), 1);
  EXPECT_EQ(count_self_intersections(pair, {1}), 1);
  const Mesh cube = testing::make_cube();
  std::vector<int> all(cube.face_count());
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(count_self_intersections(cube, all), 0);
  const Mesh sphere = testing::make_sphere(6);
  all.resize(sphere.face_count());
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(count_self_intersections(sphere, all), 0);
  // A sphere pushed through itself: one cap moved inwards across the other side.
  Mesh dented = sphere;
  for (Vec3& p : dented.positions) {
    if (p.z() > 0.8) p.z() -= 1.9;
  }
  EXPECT_GT(count_self_intersections(dented, all), 0);
}

// Crossing, touching at a point and overlapping in a plane intersect; triangles apart or
// degenerate (collinear corners) do not.
TEST(TrianglesIntersect, SharedPointsCount) {
  const std::array<Vec3, 3> flat = {Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_TRUE(triangles_intersect(flat, {Vec3(0, 0.2, -1), Vec3(0, 0.2, 1), Vec3(0, 0.5, 0.2)}));
  EXPECT_FALSE(triangles_intersect(flat, {Vec3(5, 0.2, -1), Vec3(5, 0.2, 1), Vec3(5, 0.5, 0.2)}));
  EXPECT_TRUE(triangles_intersect(flat, {Vec3(0, 0.3, 0), Vec3(0, 0.3, 1), Vec3(0.2, 0.3, 1)}));
  EXPECT_FALSE(triangles_intersect(flat, {Vec3(0, 0.3, 1e-9), Vec3(0, 0.3, 1), Vec3(0.2, 0.3, 1)}));
  EXPECT_TRUE(triangles_intersect(flat, {Vec3(0, 0.1, 0), Vec3(2, 0.1, 0), Vec3(0, 3, 0)}));
  EXPECT_FALSE(triangles_intersect(flat, {Vec3(-2, 0.5, 0), Vec3(0, 0.5, 0), Vec3(2, 0.5, 0)}));
}

// The index finds the faces a triangle meets, leaving out those that share a listed corner.
TEST(IntersectionIndex, SkipsFacesSharingAListedCorner) {
  Mesh mesh = crossing_pair();
  mesh.positions.push_back({0, -10, 0});  // face 2 beside face 0, sharing its vertices 0 and 1
  mesh = make_mesh(mesh.positions, {{0, 1, 2}, {3, 4, 5}, {0, 6, 1}});
  const IntersectionIndex index(mesh);
  // The query is face 1 itself: it meets faces 0 and 1, not face 2.
  const Vec3 a(0, 0.2, -1), b(0, 0.2, 1), c(0, 0.5, 0.2);
  EXPECT_EQ(index.intersecting_faces(a, b, c, {-1, -1, -1}), std::vector<int>({0, 1}));
  EXPECT_EQ(index.intersecting_faces(a, b, c, {3, -1, -1}), std::vector<int>({0}));
  EXPECT_EQ(index.intersecting_faces(a, b, c, {-1, 0, -1}), std::vector<int>({1}));
  EXPECT_EQ(index.intersecting_faces(a, b, c, {3, 2, -1}), std::vector<int>{});
  EXPECT_EQ(index.intersecting_faces(a, b, c, {6, -1, 5}), std::vector<int>({0}));
  EXPECT_EQ(index.intersecting_faces(Vec3(20, 0, 0), Vec3(21, 0, 0), Vec3(20, 1, 0), {-1, -1, -1}),
            std::vector<int>{});
  EXPECT_TRUE(IntersectionIndex(Mesh()).intersecting_faces(a, b, c, {-1, -1, -1}).empty());
}

}  // namespace
}  // namespace rangefill
