#include "rangefill/repair/selection.h"

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "rangefill/repair/pipeline.h"
#include "support.h"

namespace rangefill {
namespace {

// A round hole of radius 4 in a unit grid: the band test hides the faces within two rings of its
// loop, keeps more around them, and its enlarged loop runs outside the hole's, round the hidden
// points.
TEST(HideBand, HidesTheRingsRoundTheLoop) {
  const Vec3 centre(15, 15, 0);
  const Mesh sheet = testing::remove_faces(testing::make_grid(30),
                                           [&](const Vec3& p) { return (p - centre).norm() < 4; });
  const SurfaceContext surface(sheet, 0);
  const BoundaryLoop hole = testing::inner_loop(sheet);
  const std::optional<BandTest> test = hide_band(surface, hole, 2, 3);
  ASSERT_TRUE(test);
  double loop_radius = 0, loop_nearest = 1e9;
  for (int v : hole.vertices) {
    loop_radius = std::max(loop_radius, (sheet.positions[v] - centre).norm());
    loop_nearest = std::min(loop_nearest, (sheet.positions[v] - centre).norm());
  }
  ASSERT_FALSE(test->hidden.empty());
  for (const Vec3& p : test->hidden) {
    EXPECT_GE((p - centre).norm(), loop_nearest);
    EXPECT_LT((p - centre).norm(), loop_radius + 2 * std::sqrt(2.0) + 1e-9);
  }
  double enlarged_radius = 1e9;
  for (int v : test->hole.vertices) {
    enlarged_radius = std::min(enlarged_radius, (test->mesh.positions[v] - centre).norm());
  }
  EXPECT_GT(enlarged_radius, loop_radius);
  EXPECT_GT(test->hole.area, hole.area + hole.perimeter);
  // Every kept face is within five rings of the loop: nothing beyond the context was copied.
  for (const Vec3& p : test->mesh.positions) EXPECT_LT((p - centre).norm(), loop_radius + 5 * 1.5);
  // The band reaching the sheet's border makes no test.
  EXPECT_FALSE(hide_band(surface, hole, 12, 3));
}

// On a flat sheet the plane's fill lies on the hidden band; lifted, it lies off it by about the
// lift.
TEST(BandDistance, MeasuresTheFillAgainstTheHiddenBand) {
  const Vec3 centre(15, 15, 0);
  const Mesh sheet = testing::remove_faces(testing::make_grid(30),
                                           [&](const Vec3& p) { return (p - centre).norm() < 4; });
  const SurfaceContext surface(sheet, 0);
  const std::optional<BandTest> test = hide_band(surface, testing::inner_loop(sheet), 2, 3);
  ASSERT_TRUE(test);
  const SurfaceContext band_surface(test->mesh, 0);
  HoleReport report;
  std::optional<Fill> fill =
      fill_by_chain(band_surface, test->hole, {make_filler("plane:harmonic")}, {}, report);
  ASSERT_TRUE(fill);
  EXPECT_LT(band_distance(*test, *fill), 1e-6);
  for (Vec3& p : fill->points) p.z() += 0.5;
  const double lifted = band_distance(*test, *fill);
  EXPECT_GT(lifted, 0.1);
  EXPECT_LE(lifted, 0.5 + 1e-9);
}

// On a sphere the faired patch continues the curvature the plane's harmonic fill flattens: its
// band test scores better, it fills the hole, and its fill stays on the sphere.
TEST(FillBySelection, FillsWithTheCandidateNearestTheHiddenBand) {
  const Mesh holed =
      testing::remove_faces(testing::make_sphere(16), [](const Vec3& p) { return p.z() > 0.85; });
  const SurfaceContext surface(holed, 0);
  const BoundaryLoop& hole = surface.holes.loops.at(0);
  SelectionOptions selection;
  selection.candidates = make_fillers("plane:harmonic,fairing");
  HoleReport report;
  const std::optional<Fill> fill = fill_by_selection(
      surface, hole, selection, {make_filler("plane:harmonic")}, ChainOptions(), report);
  ASSERT_TRUE(fill);
  ASSERT_EQ(report.selection.size(), 2u);
  ASSERT_TRUE(report.selection[0].score && report.selection[1].score);
  EXPECT_LT(*report.selection[1].score, 0.5 * *report.selection[0].score);
  EXPECT_EQ(report.selected, "fairing");
  EXPECT_EQ(report.filler, "fairing");
  for (const Vec3& p : fill->points) EXPECT_NEAR(p.norm(), 1.0, 0.01);
}

// The repair's default scores every hole's candidates and reports the one that filled it.
TEST(FillBySelection, TheDefaultRepairReportsTheWinner) {
  const Mesh holed = testing::remove_faces(
      testing::make_sphere(16), [](const Vec3& p) { return p.z() > 0.9 || p.x() > 0.92; });
  const RepairResult result = repair(holed);
  ASSERT_EQ(result.holes.size(), 2u);
  for (const HoleReport& hole : result.holes) {
    EXPECT_TRUE(hole.filled);
    EXPECT_EQ(hole.selection.size(), RepairOptions().selection.candidates.size());
    EXPECT_FALSE(hole.selected.empty());
  }
  testing::expect_input_preserved(holed, result.mesh);
}

}  // namespace
}  // namespace rangefill
