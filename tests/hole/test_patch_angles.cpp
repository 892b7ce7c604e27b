#include "rangefill/hole/patch_angles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "rangefill/core/intersection.h"
#include "rangefill/image/stitch.h"
#include "support.h"

namespace rangefill {
namespace {

constexpr int kGrid = 8;

// make_grid(8) with the 4×4 square [2, 6]² removed, and the removed grid as the hole's fill: its
// 3×3 inner vertices as the new points, the removed triangles as they were.
struct SquareHole {
  Mesh mesh;
  MeshTopology topology;
  Fill fill;
};

bool in_square(const Vec3& p) {
  return p.x() >= 2 && p.x() <= 6 && p.y() >= 2 && p.y() <= 6;
}

SquareHole make_square_hole() {
  const Mesh grid = testing::make_grid(kGrid);
  SquareHole square{testing::remove_faces(grid, in_square), {}, {}};
  square.topology = build_topology(square.mesh);
  square.fill.boundary = testing::inner_loop(square.mesh).vertices;
  std::map<int, int> fill_id;
  for (size_t i = 0; i < square.fill.boundary.size(); ++i) {
    fill_id[square.fill.boundary[i]] = static_cast<int>(i);
  }
  for (const Triangle& t : grid.triangles) {
    if (!(in_square(grid.positions[t[0]]) && in_square(grid.positions[t[1]]) &&
          in_square(grid.positions[t[2]]))) {
      continue;
    }
    Triangle corners;
    for (int k = 0; k < 3; ++k) {
      auto [entry, added] = fill_id.emplace(
          t[k], static_cast<int>(square.fill.boundary.size() + square.fill.points.size()));
      if (added) square.fill.points.push_back(grid.positions[t[k]]);
      corners[k] = entry->second;
    }
    square.fill.triangles.push_back(corners);
  }
  return square;
}

// The fill's area (the plane's square is 16).
double fill_area(const Mesh& mesh, const Fill& fill) {
  const int boundary_size = static_cast<int>(fill.boundary.size());
  const auto position = [&](int v) {
    return v < boundary_size ? mesh.positions[fill.boundary[v]] : fill.points[v - boundary_size];
  };
  double area = 0;
  for (const Triangle& t : fill.triangles) {
    area += (position(t[1]) - position(t[0])).cross(position(t[2]) - position(t[0])).norm() / 2;
  }
  return area;
}

// EXPECTs that `after` is the square's fill with the same loop, its points (and any added, each
// adding two triangles) in the square's plane and inside it, covering the square once: the
// surface is kept, only the triangles change.
void expect_same_surface(const SquareHole& square, const Fill& after) {
  EXPECT_EQ(after.boundary, square.fill.boundary);
  ASSERT_GE(after.points.size(), square.fill.points.size());
  const auto euler = [](const Fill& fill) {
    return static_cast<long>(fill.triangles.size()) - 2 * static_cast<long>(fill.points.size());
  };
  EXPECT_EQ(euler(after), euler(square.fill));
  for (const Vec3& p : after.points) {
    EXPECT_NEAR(p.z(), 0, 1e-12);
    EXPECT_TRUE(in_square(p)) << p.transpose();
  }
  EXPECT_NEAR(fill_area(square.mesh, after), 16, 1e-9);
  EXPECT_FALSE(fill_defect(square.mesh, square.topology, after));
}

// An inner point pulled 0.85 towards its neighbour (a remeshed patch faired again does this near
// short loop edges) leaves an 8° sliver; smoothing over the plane moves it back among its
// neighbours, where every angle is over 30°.
TEST(WithLargerAngles, MovesAPointThatMakesASliverBackAmongItsNeighbours) {
  SquareHole square = make_square_hole();
  for (Vec3& p : square.fill.points) {
    if (p.x() == 3 && p.y() == 3) p.y() = 3.85;
  }
  ASSERT_LT(testing::smallest_angle(square.mesh, square.fill), 10);
  const Fill after = with_larger_angles(square.mesh, square.topology, square.fill);
  expect_same_surface(square, after);
  EXPECT_GT(testing::smallest_angle(square.mesh, after), 30);
}

// A fan from one point near a corner, slivers towards the far sides, opens up: flips and the
// point's move leave no angle under 10°.
TEST(WithLargerAngles, FlipsAFanOfSliversOpen) {
  SquareHole square = make_square_hole();
  const int boundary_size = static_cast<int>(square.fill.boundary.size());
  square.fill.points = {Vec3(2.5, 2.5, 0)};
  square.fill.triangles.clear();
  for (int i = 0; i < boundary_size; ++i) {
    square.fill.triangles.push_back({(i + 1) % boundary_size, i, boundary_size});
  }
  if (fill_defect(square.mesh, square.topology, square.fill)) {  // the loop runs the other way
    for (Triangle& t : square.fill.triangles) std::swap(t[0], t[1]);
  }
  ASSERT_FALSE(fill_defect(square.mesh, square.topology, square.fill));
  ASSERT_LT(testing::smallest_angle(square.mesh, square.fill), 5);
  const Fill after = with_larger_angles(square.mesh, square.topology, square.fill);
  expect_same_surface(square, after);
  EXPECT_GE(testing::smallest_angle(square.mesh, after), 10);
}

// A loop vertex slid along the square's side, 0.15 from its neighbour: the grid's triangle on that
// short edge has its apex a grid step away (a 7° sliver) and no point can move there without
// making others worse; a point added on its longest inner edge and smoothed into place can.
TEST(WithLargerAngles, AddsAPointNearAShortLoopEdge) {
  const Mesh grid = testing::make_grid(kGrid);
  const int slid = 2 * (kGrid + 1) + 3;  // (3, 2) on the square's lower side
  ASSERT_EQ(grid.positions[slid], Vec3(3, 2, 0));
  SquareHole square = make_square_hole();
  square.mesh.positions[slid] = Vec3(2.15, 2, 0);
  square.topology = build_topology(square.mesh);
  ASSERT_LT(testing::smallest_angle(square.mesh, square.fill), 10);
  const Fill after = with_larger_angles(square.mesh, square.topology, square.fill);
  expect_same_surface(square, after);
  EXPECT_GT(after.points.size(), square.fill.points.size());
  EXPECT_GE(testing::smallest_angle(square.mesh, after), 10);
}

// A dart-shaped hole a → b → c → d (d the reflex corner) in a flat square, the notch below d
// covered by two faces, and a fill folded over that notch: the triangle (a, b, c) covers the notch,
// (a, c, d) folds back onto it. Flipping their edge untangles it.
TEST(WithLargerAngles, UntanglesAFillFoldedOverTheSurface) {
  const Vec3 a(0, 0, 0), b(2, 4, 0), c(4, 0, 0), d(2, 1, 0), e(2, -1, 0);
  const Vec3 p0(-2, -2, 0), p1(6, -2, 0), p2(6, 6, 0), p3(-2, 6, 0);
  enum { A, B, C, D, E, P0, P1, P2, P3 };
  const Mesh mesh = make_mesh({a, b, c, d, e, p0, p1, p2, p3}, {{A, E, D},
                                                                {E, C, D},
                                                                {P0, P1, E},
                                                                {P1, C, E},
                                                                {P1, P2, C},
                                                                {C, P2, B},
                                                                {B, P2, P3},
                                                                {A, B, P3},
                                                                {P0, A, P3},
                                                                {P0, E, A}});
  const MeshTopology topology = build_topology(mesh);
  Fill fill;
  fill.boundary = {A, B, C, D};  // the faces run a → b → c → d along the loop
  fill.triangles = {{2, 1, 0}, {0, 3, 2}};
  ASSERT_FALSE(fill_defect(mesh, topology, fill));
  const IntersectionIndex surface(mesh);
  const auto crossings = [&](const Fill& f) {
    int count = 0;
    for (const Triangle& t : f.triangles) {
      const Triangle corners = {f.boundary[t[0]], f.boundary[t[1]], f.boundary[t[2]]};
      count += static_cast<int>(surface
                                    .intersecting_faces(mesh.positions[corners[0]],
                                                        mesh.positions[corners[1]],
                                                        mesh.positions[corners[2]], corners)
                                    .size());
    }
    return count;
  };
  ASSERT_GT(crossings(fill), 0);

  const Fill after = with_larger_angles(mesh, topology, fill);
  EXPECT_EQ(crossings(after), 0);
  EXPECT_FALSE(fill_defect(mesh, topology, after));
  EXPECT_NEAR(fill_area(mesh, after), 6, 1e-12);  // the dart's area: nothing folds any more
}

// A fill whose loop passes one vertex twice is returned as it is.
TEST(WithLargerAngles, LeavesAFillOfAPinchedLoopAsItIs) {
  SquareHole square = make_square_hole();
  square.fill.boundary.push_back(square.fill.boundary.front());
  const Fill after = with_larger_angles(square.mesh, square.topology, square.fill);
  EXPECT_EQ(after.triangles, square.fill.triangles);
  testing::expect_bit_identical(after.points, square.fill.points);
}

}  // namespace
}  // namespace rangefill
