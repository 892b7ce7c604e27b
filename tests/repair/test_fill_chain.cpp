#include "rangefill/repair/fill_chain.h"

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "rangefill/fillers/fairing.h"
#include "rangefill/repair/filler_options.h"
#include "rangefill/repair/fillers.h"
#include "rangefill/repair/pipeline.h"
#include "support.h"

namespace rangefill {
namespace {

// --filler and --fallback spell the chain in the order given; with planes in it, the parts of a
// complex hole come before the loop's patches.
TEST(MakeFillerChain, SpellsTheFillerAndItsFallbacks) {
  using Names = std::vector<std::string>;
  const auto names = [](const std::string& filler, const std::string& fallbacks) {
    return filler_chain_names(make_filler_chain(filler, fallbacks));
  };
  EXPECT_EQ(names(kDefaultFiller, kDefaultFallbacks),
            (Names{"fairing", "plane", "front", "plane-in-part", "liepa", "least-area"}));
  EXPECT_EQ(filler_chain_names(RepairOptions().chain), names(kDefaultFiller, kDefaultFallbacks));
  EXPECT_EQ(names("plane", "none"), (Names{"plane", "plane-in-part"}));
  EXPECT_EQ(names("plane", "least-area,front"),
            (Names{"plane", "plane-in-part", "liepa", "least-area", "front"}));
  EXPECT_EQ(names("front", "least-area"), (Names{"front", "liepa", "least-area"}));
  EXPECT_EQ(names("front", "none"), (Names{"front"}));
  EXPECT_EQ(names("front", "fairing"), (Names{"front", "fairing"}));
  EXPECT_THROW(make_filler_chain("plane", "front,fronts"), InvalidInput);
  EXPECT_EQ(names("plane", kDefaultFallbacks),
            (Names{"plane", "front", "plane-in-part", "liepa", "least-area"}));
  EXPECT_THROW(make_filler("planes"), InvalidInput);
  EXPECT_THROW(make_filler("fairing:c3"), InvalidInput);
  EXPECT_THROW(make_filler("front:telea"), InvalidInput);
  EXPECT_EQ(make_filler("plane-in-part")->method(), "plane, in part");
  EXPECT_EQ(make_filler("fairing:c1")->name(), "fairing:c1");
  for (const std::string& name : filler_names()) EXPECT_EQ(make_filler(name)->name(), name);
  EXPECT_EQ(filler_chain_names(make_fillers("fairing,plane:telea,front")),
            (Names{"fairing", "plane:telea", "front"}));
  EXPECT_TRUE(make_fillers("none").empty());
  EXPECT_THROW(make_fillers("front,front"), InvalidInput);
  EXPECT_THROW(make_fillers("fairing,"), InvalidInput);
}

// A round hole in a flat sheet: the plane fills it first; with the loop's patches only, Liepa's;
// an island inside a hole makes every filler refuse, each refusal recorded with its filler.
TEST(FillByChain, TakesTheFirstFillerThatFillsAndRecordsTheRefusals) {
  const Mesh sheet = testing::remove_faces(
      testing::make_grid(20), [](const Vec3& p) { return (p - Vec3(10, 10, 0)).norm() < 4; });
  const SurfaceContext surface(sheet, 0);
  const BoundaryLoop hole = testing::inner_loop(sheet);
  FillerOptions fillers;
  fillers.plane.inpainter = "harmonic";
  const FillerChain paper = make_filler_chain("plane", "front,least-area", fillers);
  const ChainOptions options;
  HoleReport plane;
  ASSERT_TRUE(fill_by_chain(surface, hole, paper, options, plane));
  EXPECT_EQ(plane.filler, "plane");
  EXPECT_EQ(plane.method, "plane");
  EXPECT_TRUE(plane.attempts.empty());
  EXPECT_GT(plane.image.masked_pixels, 0);
  for (const char* step : {"zone", "plane", "checking", "image", "inpainting", "stitching"}) {
    EXPECT_GT(seconds_of(plane.steps, step), 0) << step;
  }

  HoleReport patch;
  const std::optional<Fill> fill =
      fill_by_chain(surface, hole, {make_filler("liepa")}, options, patch);
  ASSERT_TRUE(fill);
  EXPECT_EQ(patch.filler, "liepa");
  EXPECT_EQ(patch.method, "Liepa");
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
  HoleReport refused;
  EXPECT_FALSE(fill_by_chain(around, outer, paper, options, refused));
  EXPECT_FALSE(refused.filled);
  ASSERT_GE(refused.attempts.size(), paper.size());
  std::vector<std::string> tried;
  for (const Attempt& attempt : refused.attempts) {
    ASSERT_FALSE(attempt.filler.empty());
    if (tried.empty() || tried.back() != attempt.filler) tried.push_back(attempt.filler);
  }
  EXPECT_EQ(tried, filler_chain_names(paper));
  // The plane's fill and Liepa's patch both cover the island.
  EXPECT_EQ(refused.attempts.front().refused.refusal, Refusal::intersects);
  for (const Attempt& attempt : refused.attempts) {
    if (attempt.filler == "liepa") {
      EXPECT_EQ(attempt.refused.refusal, Refusal::intersects);
    }
  }
  EXPECT_EQ(refused.failure.rfind("hole " + std::to_string(outer.id) + ": plane: ", 0), 0u)
      << refused.failure;
}

// Without the angle pass the acceptance step takes each filler's fill as it is (the band test
// scores those); by default the pass reshapes it.
TEST(FillByChain, GivesLargerAnglesUnlessTheAcceptanceSaysNot) {
  const Mesh sheet = testing::remove_faces(
      testing::make_grid(20), [](const Vec3& p) { return (p - Vec3(10, 10.3, 0)).norm() < 4.6; });
  const SurfaceContext surface(sheet, 0);
  const BoundaryLoop hole = testing::inner_loop(sheet);
  const FillerChain fairing = {make_filler("fairing")};
  const Fill raw = std::get<Fill>(
      fill_by_fairing(sheet, surface.topology, hole, surface.mean_edge, FairingOptions()));
  ChainOptions options;
  HoleReport report;
  const std::optional<Fill> angled = fill_by_chain(surface, hole, fairing, options, report);
  options.acceptance.larger_angles = false;
  const std::optional<Fill> as_made = fill_by_chain(surface, hole, fairing, options, report);
  ASSERT_TRUE(angled && as_made);
  EXPECT_EQ(as_made->points, raw.points);
  EXPECT_EQ(as_made->triangles, raw.triangles);
  EXPECT_TRUE(angled->points != raw.points || angled->triangles != raw.triangles);
}

// A filler that throws ProcessingError is refused with its message; the next one fills.
TEST(FillByChain, RefusesAFillerThatThrows) {
  class Throwing : public Filler {
   public:
    std::string name() const override { return "throwing"; }
    std::string method() const override { return "throwing"; }
    FillOutcome fill(const HoleContext&, const AcceptFill&, FillerLog&) const override {
      throw ProcessingError("out of luck");
    }
  };
  const Mesh sheet = testing::remove_faces(
      testing::make_grid(20), [](const Vec3& p) { return (p - Vec3(10, 10, 0)).norm() < 4; });
  const SurfaceContext surface(sheet, 0);
  HoleReport report;
  ASSERT_TRUE(fill_by_chain(surface, testing::inner_loop(sheet),
                            {std::make_shared<Throwing>(), make_filler("liepa")}, ChainOptions(),
                            report));
  EXPECT_EQ(report.filler, "liepa");
  ASSERT_EQ(report.attempts.size(), 1u);
  EXPECT_EQ(report.attempts[0].filler, "throwing");
  EXPECT_EQ(report.attempts[0].refused.refusal, Refusal::error);
  EXPECT_EQ(report.attempts[0].refused.detail, "out of luck");
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
