#include "rangefill/repair/fill_chain.h"

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "rangefill/repair/fairing.h"
#include "support.h"

namespace rangefill {
namespace {

// --filler and --fallback spell the chain in the order given; with planes in it, the parts of a
// complex hole come before the loop's patches.
TEST(StrategyChain, SpellsTheFillerAndItsFallbacks) {
  using S = Strategy;
  EXPECT_EQ(
      strategy_chain(kDefaultFiller, kDefaultFallbacks),
      (std::vector<S>{S::fairing, S::plane, S::front, S::plane_in_part, S::liepa, S::least_area}));
  EXPECT_EQ(FillOptions().strategies, strategy_chain(kDefaultFiller, kDefaultFallbacks));
  EXPECT_EQ(strategy_chain(Filler::plane, "none"), (std::vector<S>{S::plane, S::plane_in_part}));
  EXPECT_EQ(strategy_chain(Filler::plane, "least-area,front"),
            (std::vector<S>{S::plane, S::plane_in_part, S::liepa, S::least_area, S::front}));
  EXPECT_EQ(strategy_chain(Filler::front, "least-area"),
            (std::vector<S>{S::front, S::liepa, S::least_area}));
  EXPECT_EQ(strategy_chain(Filler::front, "none"), (std::vector<S>{S::front}));
  EXPECT_EQ(strategy_chain(Filler::front, "fairing"), (std::vector<S>{S::front, S::fairing}));
  EXPECT_THROW(strategy_chain(Filler::plane, "front,fronts"), InvalidInput);
  EXPECT_EQ(strategy_chain(Filler::plane, kDefaultFallbacks),
            (std::vector<S>{S::plane, S::front, S::plane_in_part, S::liepa, S::least_area}));
  EXPECT_EQ(filler_from_name(filler_name(Filler::fairing)), Filler::fairing);
  EXPECT_THROW(filler_from_name("planes"), InvalidInput);
  EXPECT_EQ(strategy_name(S::plane_in_part), "plane, in part");
}

// A round hole in a flat sheet: the plane fills it first; with the loop's patches only, Liepa's;
// an island inside a hole makes every strategy refuse, each refusal recorded with its strategy.
TEST(FillByChain, TakesTheFirstStrategyThatFillsAndRecordsTheRefusals) {
  const Mesh sheet = testing::remove_faces(
      testing::make_grid(20), [](const Vec3& p) { return (p - Vec3(10, 10, 0)).norm() < 4; });
  const SurfaceContext surface(sheet, 0);
  const BoundaryLoop hole = testing::inner_loop(sheet);
  const std::unique_ptr<Inpainter> inpainter = make_inpainter("harmonic");
  FillOptions options;
  options.strategies = strategy_chain(Filler::plane, "front,least-area");
  HoleReport plane;
  ASSERT_TRUE(fill_by_chain(surface, hole, *inpainter, options, false, plane));
  EXPECT_EQ(plane.strategy, Strategy::plane);
  EXPECT_TRUE(plane.attempts.empty());

  options.strategies = {Strategy::liepa};
  HoleReport patch;
  const std::optional<Fill> fill = fill_by_chain(surface, hole, *inpainter, options, false, patch);
  ASSERT_TRUE(fill);
  EXPECT_EQ(patch.strategy, Strategy::liepa);
  EXPECT_TRUE(fill->points.empty());

  const Mesh island = testing::remove_faces(testing::make_grid(40), [](const Vec3& p) {
    const double r = (p - Vec3(20, 20, 0)).norm();
    return r > 3 && r < 10;
  });
  const SurfaceContext around(island, 0);
  BoundaryLoop outer;
  for (const BoundaryLoop& loop : around.holes.loops) {
    if (loop.vertices.size() == 64) outer = loop;  // the hole's outer loop, round the island
  }
  ASSERT_FALSE(outer.vertices.empty());
  options.strategies = strategy_chain(Filler::plane, "front,least-area");
  HoleReport refused;
  EXPECT_FALSE(fill_by_chain(around, outer, *inpainter, options, false, refused));
  EXPECT_FALSE(refused.filled);
  ASSERT_GE(refused.attempts.size(), options.strategies.size());
  std::vector<Strategy> tried;
  for (const Attempt& attempt : refused.attempts) {
    ASSERT_TRUE(attempt.strategy);
    if (tried.empty() || tried.back() != *attempt.strategy) tried.push_back(*attempt.strategy);
  }
  EXPECT_EQ(tried, options.strategies);
  // The plane's fill and Liepa's patch both cover the island.
  EXPECT_EQ(refused.attempts.front().refused.refusal, Refusal::intersects);
  for (const Attempt& attempt : refused.attempts) {
    if (attempt.strategy == Strategy::liepa) {
      EXPECT_EQ(attempt.refused.refusal, Refusal::intersects);
    }
  }
  EXPECT_EQ(refused.failure.rfind("hole " + std::to_string(outer.id) + ": plane: ", 0), 0u)
      << refused.failure;
}

// A surface that does not ask for larger angles gets each filler's fill as it is (the band test
// scores those); by default the angle pass reshapes it.
TEST(FillByChain, GivesLargerAnglesUnlessTheSurfaceSaysNot) {
  const Mesh sheet = testing::remove_faces(
      testing::make_grid(20), [](const Vec3& p) { return (p - Vec3(10, 10.3, 0)).norm() < 4.6; });
  SurfaceContext surface(sheet, 0);
  const BoundaryLoop hole = testing::inner_loop(sheet);
  const std::unique_ptr<Inpainter> inpainter = make_inpainter("harmonic");
  FillOptions options;
  options.strategies = {Strategy::fairing};
  const Fill raw = std::get<Fill>(
      fill_by_fairing(sheet, surface.topology, hole, surface.mean_edge, options.fairing));
  HoleReport report;
  const std::optional<Fill> angled =
      fill_by_chain(surface, hole, *inpainter, options, false, report);
  surface.larger_angles = false;
  const std::optional<Fill> as_made =
      fill_by_chain(surface, hole, *inpainter, options, false, report);
  ASSERT_TRUE(angled && as_made);
  EXPECT_EQ(as_made->points, raw.points);
  EXPECT_EQ(as_made->triangles, raw.triangles);
  EXPECT_TRUE(angled->points != raw.points || angled->triangles != raw.triangles);
}

// Every refusal has words.
TEST(Refusal, EachHasItsText) {
  for (const Refusal refusal :
       {Refusal::nonmanifold_rim, Refusal::empty_zone, Refusal::no_plane, Refusal::partial_view,
        Refusal::not_manifold, Refusal::intersects, Refusal::front_stuck, Refusal::no_part,
        Refusal::no_triangulation, Refusal::error}) {
    EXPECT_FALSE(refusal_text(refusal).empty());
  }
}

}  // namespace
}  // namespace rangefill
