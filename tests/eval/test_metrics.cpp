// Measuring repairs (metrics.h, evaluation.h): surface distances with known answers, manifold
// checks, provenance queries, and scoring a repair of punched holes.
#include "rangefill/eval/metrics.h"

#include <cmath>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "rangefill/eval/evaluation.h"
#include "support.h"

namespace rangefill {
namespace {

// The rectangle [0, width] × [0, 1] at height z, as two triangles facing +z.
Mesh rectangle(double width, double z) {
  return make_mesh({{0, 0, z}, {width, 0, z}, {width, 1, z}, {0, 1, z}}, {{0, 1, 2}, {0, 2, 3}});
}

const std::vector<int> kBoth = {0, 1};

// The unit square and the same square 0.1 above it: every sample of either is 0.1 from the other,
// so all four figures are 0.1.
TEST(SurfaceDistance, ParallelSquaresAreTheirOffsetApart) {
  const SurfaceDistance d =
      surface_distance(rectangle(1, 0), kBoth, rectangle(1, 0.1), kBoth, 0.05);
  EXPECT_NEAR(d.hausdorff, 0.1, 1e-12);
  EXPECT_NEAR(d.from_first, 0.1, 1e-12);
  EXPECT_NEAR(d.from_second, 0.1, 1e-12);
  EXPECT_NEAR(d.mean, 0.1, 1e-12);
}

// Points above, beside and on the unit square: their distances to its faces, exactly; only the
// faces asked for count (the right half alone is farther from a point over the left half).
TEST(DistancesToFaces, AreThePointsDistancesToTheChosenFaces) {
  const Mesh square = rectangle(1, 0);
  const std::vector<double> d =
      distances_to_faces({{0.25, 0.5, 0.3}, {2, 0.5, 0}, {0.5, 0.5, 0}}, square, kBoth);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_NEAR(d[0], 0.3, 1e-12);
  EXPECT_NEAR(d[1], 1.0, 1e-12);
  EXPECT_NEAR(d[2], 0.0, 1e-12);
  const Mesh two = make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}},
                             {{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 2}});
  EXPECT_NEAR(distances_to_faces({{0.25, 0.5, 0}}, two, {2, 3})[0], 0.75, 1e-12);
  EXPECT_THROW(distances_to_faces({{0, 0, 0}}, square, {}), InvalidInput);
}

// The unit square against its left half: the half lies on the square (0 from it), the square's
// right edge is 0.5 from the half.
TEST(SurfaceDistance, OneSidedDistancesDifferForASubset) {
  const Mesh square = rectangle(1, 0), half = rectangle(0.5, 0);
  const SurfaceDistance d = surface_distance(square, kBoth, half, kBoth, 0.05);
  EXPECT_NEAR(d.from_first, 0.5, 1e-12);
  EXPECT_NEAR(d.from_second, 0, 1e-12);
  EXPECT_NEAR(d.hausdorff, 0.5, 1e-12);
  // The square's samples are max(0, x − 0.5) from the half (0.125 on average over the square),
  // the half's are 0: the mean is the average of the two sides' means.
  EXPECT_NEAR(d.mean, 0.5 * 0.125, 0.005);
  const SurfaceDistance swapped = surface_distance(half, kBoth, square, kBoth, 0.05);
  EXPECT_NEAR(swapped.from_first, 0, 1e-12);
  EXPECT_NEAR(swapped.from_second, 0.5, 1e-12);
  // Only the listed faces count: the square's lower-right triangle {0, 1, 2} alone.
  EXPECT_NEAR(surface_distance(square, {0}, half, kBoth, 0.05).from_first, 0.5, 1e-12);
  EXPECT_NEAR(surface_distance(square, {1}, half, kBoth, 0.05).from_first, 0.5, 1e-12);
  EXPECT_NEAR(surface_distance(half, {1}, square, {1}, 0.05).from_first, 0, 1e-12);
}

// An empty face set or a non-positive spacing is refused.
TEST(SurfaceDistance, RefusesEmptySetsAndBadSpacing) {
  const Mesh square = rectangle(1, 0);
  EXPECT_THROW(surface_distance(square, {}, square, kBoth, 0.1), InvalidInput);
  EXPECT_THROW(surface_distance(square, kBoth, square, {}, 0.1), InvalidInput);
  EXPECT_THROW(surface_distance(square, kBoth, square, kBoth, 0), InvalidInput);
  EXPECT_THROW(surface_distance(square, kBoth, square, kBoth, -1), InvalidInput);
}

// The cube is a closed manifold; without its top it has one boundary loop; an edge with three
// faces, two faces running an edge the same way, and two fans meeting at a vertex are counted.
TEST(CheckManifold, CountsWhatIsWrong) {
  EXPECT_TRUE(check_manifold(testing::make_cube()).closed_manifold());
  Mesh open = testing::make_cube();
  open.triangles.erase(open.triangles.begin() + 2, open.triangles.begin() + 4);  // z = 1
  open.face_hole.resize(open.triangles.size());
  const ManifoldCheck without_top = check_manifold(open);
  EXPECT_FALSE(without_top.closed_manifold());
  EXPECT_EQ(without_top.boundary_loops, 1);
  EXPECT_EQ(without_top.nonmanifold_edges + without_top.misoriented_edges +
                without_top.nonmanifold_vertices,
            0);

  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  EXPECT_EQ(check_manifold(make_mesh(points, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}})).nonmanifold_edges,
            1);
  EXPECT_EQ(check_manifold(make_mesh(points, {{0, 1, 2}, {0, 1, 3}})).misoriented_edges, 1);
  const std::vector<Vec3> bowtie = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  EXPECT_EQ(check_manifold(make_mesh(bowtie, {{0, 1, 2}, {0, 3, 4}})).nonmanifold_vertices, 1);
}

// faces_of_hole selects by provenance; kAnyHole takes every generated face.
TEST(FacesOfHole, SelectsByProvenance) {
  Mesh mesh = testing::make_cube();
  mesh.face_hole = {kOriginal, 2, 2,         5, kOriginal, kOriginal,
                    5,         0, kOriginal, 2, kOriginal, kOriginal};
  EXPECT_EQ(faces_of_hole(mesh, 2), (std::vector<int>{1, 2, 9}));
  EXPECT_EQ(faces_of_hole(mesh, 5), (std::vector<int>{3, 6}));
  EXPECT_EQ(faces_of_hole(mesh, 0), (std::vector<int>{7}));
  EXPECT_EQ(faces_of_hole(mesh, kAnyHole), (std::vector<int>{1, 2, 3, 6, 7, 9}));
  EXPECT_TRUE(faces_of_hole(mesh, 4).empty());
}

// The mean length of the unique edges of the listed faces.
TEST(MeanEdgeLength, OfListedFaces) {
  const Mesh square = rectangle(1, 0);
  EXPECT_NEAR(mean_edge_length(square, kBoth), (4 + std::sqrt(2.0)) / 5, 1e-15);
  EXPECT_NEAR(mean_edge_length(square, {0}), (2 + std::sqrt(2.0)) / 3, 1e-15);
  EXPECT_EQ(mean_edge_length(square, std::vector<int>{}), 0);
}

// A sphere with four punched holes, repaired with the defaults: every hole is scored as filled
// with a patch whose symmetric Hausdorff distance to the removed faces is below d_m, with edges
// of about d_m; a hole left out of the repair is scored "not attempted".
TEST(ScoreRepair, RepairedSphereHolesAreCloseToTheTruth) {
  const Mesh sphere = testing::make_sphere(16);
  const double mean_edge = mean_edge_length(sphere);
  PunchOptions punch;
  punch.holes = 4;
  punch.seed = 3;
  punch.min_radius = 3;
  punch.max_radius = 5;
  const PunchResult punched = punch_holes(sphere, punch);
  ASSERT_EQ(punched.holes.size(), 4u);
  const RepairResult repaired = repair(punched.mesh);
  const std::vector<HoleScore> scores = score_repair(sphere, punched, repaired, mean_edge);
  ASSERT_EQ(scores.size(), 4u);
  for (const HoleScore& score : scores) {
    SCOPED_TRACE("hole " + std::to_string(score.hole) + " (" + score.method + ")");
    EXPECT_TRUE(score.filled) << score.failure;
    EXPECT_LT(score.distance.hausdorff, mean_edge);
    EXPECT_LT(score.distance.mean, 0.1 * mean_edge);
    EXPECT_GT(score.distance.hausdorff, 0);
    EXPECT_GT(score.new_faces, 0);
    EXPECT_GT(score.edge_ratio, 0.5);
    EXPECT_LT(score.edge_ratio, 2);
    double area = 0;
    for (int f : punched.holes[score.hole].removed_faces)
      area += 0.5 * triangle_cross(sphere, f).norm();
    EXPECT_DOUBLE_EQ(score.area, area);
  }
  EXPECT_TRUE(check_manifold(repaired.mesh).closed_manifold());

  RepairOptions only_one;
  only_one.holes = {0};
  const std::vector<HoleScore> partial =
      score_repair(sphere, punched, repair(punched.mesh, only_one), mean_edge);
  int attempted = 0;
  for (const HoleScore& score : partial) {
    if (score.failure == "not attempted") {
      EXPECT_FALSE(score.filled);
    } else {
      ++attempted;
      EXPECT_TRUE(score.filled) << score.failure;
    }
  }
  EXPECT_EQ(attempted, 1);
}

}  // namespace
}  // namespace rangefill
