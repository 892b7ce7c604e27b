// The benchmark's library side (evaluation.h): one method on one punched hole, scored against the
// removed faces on hand-made patches; a failing method is a failure of that hole alone; the
// aggregates of Section X (ranking, Pearson, classes, mean ± sd) on hand-made numbers.
#include "rangefill/eval/evaluation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "support.h"

namespace rangefill {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// A box of 20×20 grids with a flat round hole in its top side: the faces within 0.2 of its middle.
struct FlatHole {
  Mesh box = testing::make_box(20);
  PunchResult punched;
  double mean_edge = mean_edge_length(box);
  FlatHole() {
    PunchedHole hole;
    for (int f = 0; f < box.face_count(); ++f) {
      const Triangle& t = box.triangles[f];
      if (std::all_of(t.begin(), t.end(),
                      [&](int v) { return (box.positions[v] - Vec3(0.5, 0.5, 1)).norm() < 0.2; })) {
        hole.removed_faces.push_back(f);
      }
    }
    punched = remove_holes(box, {hole});
  }
};

const FlatHole& flat_hole() {
  static const FlatHole hole;
  return hole;
}

// A method that fills the hole with the very faces removed, their inner vertices (those not on the
// hole's loop) raised by `shift`.
BenchmarkMethod truth_method(double shift) {
  return {"truth", [shift](const Mesh& mesh, int loop, const ImagesCallback&) {
            const FlatHole& flat = flat_hole();
            RepairResult result;
            result.mesh = mesh;
            std::vector<int> index(flat.box.vertex_count(), -1);
            for (size_t v = 0; v < flat.punched.original_vertex.size(); ++v)
              index[flat.punched.original_vertex[v]] = static_cast<int>(v);
            for (int f : flat.punched.holes[0].removed_faces) {
              Triangle t;
              for (int k = 0; k < 3; ++k) {
                const int v = flat.box.triangles[f][k];
                if (index[v] < 0)
                  index[v] =
                      add_vertex(result.mesh, flat.box.positions[v] + Vec3(0, 0, shift), loop);
                t[k] = index[v];
              }
              add_face(result.mesh, t, loop);
            }
            HoleReport report;
            report.id = report.loop = loop;
            report.filled = true;
            report.method = "truth";
            report.new_faces = static_cast<int>(flat.punched.holes[0].removed_faces.size());
            result.holes.push_back(report);
            return result;
          }};
}

HoleRun run_on_flat_hole(const BenchmarkMethod& method) {
  const FlatHole& flat = flat_hole();
  const std::vector<int> loops = punched_loops(flat.box, flat.punched);
  EXPECT_EQ(loops, std::vector<int>{0});
  return run_method_on_hole(flat.box, flat.punched, 0, loops.at(0), method, flat.mean_edge);
}

// A patch equal to the removed faces scores 0 on every distance, closes the hole and has the
// removed faces' edge ratio.
TEST(RunMethodOnHole, PatchEqualToTheTruthScoresZero) {
  const FlatHole& flat = flat_hole();
  ASSERT_GT(flat.punched.holes[0].removed_faces.size(), 20u);
  const HoleRun run = run_on_flat_hole(truth_method(0));
  EXPECT_TRUE(run.score.filled) << run.score.failure;
  EXPECT_NEAR(run.score.distance.hausdorff, 0, 1e-12);
  EXPECT_NEAR(run.score.distance.from_first, 0, 1e-12);
  EXPECT_NEAR(run.score.distance.from_second, 0, 1e-12);
  EXPECT_NEAR(run.score.distance.mean, 0, 1e-12);
  EXPECT_DOUBLE_EQ(
      run.score.edge_ratio,
      mean_edge_length(flat.box, flat.punched.holes[0].removed_faces) / flat.mean_edge);
  EXPECT_EQ(run.patch.face_count(), static_cast<int>(flat.punched.holes[0].removed_faces.size()));
  EXPECT_TRUE(run.manifold);
  EXPECT_EQ(run.self_intersections, 0);
  EXPECT_TRUE(run.depth.empty());  // no range image
}

// A patch whose inner vertices are raised by h scores h: its raised faces lie h above the truth,
// the truth's middle lies h below them, nothing is farther; the mean is below h (the rim slopes).
TEST(RunMethodOnHole, PatchShiftedByHScoresH) {
  const double h = 0.05 * flat_hole().mean_edge;
  const HoleRun run = run_on_flat_hole(truth_method(h));
  EXPECT_TRUE(run.score.filled) << run.score.failure;
  EXPECT_NEAR(run.score.distance.hausdorff, h, 1e-12);
  EXPECT_NEAR(run.score.distance.from_first, h, 1e-12);
  EXPECT_NEAR(run.score.distance.from_second, h, 1e-12);
  EXPECT_GT(run.score.distance.mean, 0.5 * h);
  EXPECT_LT(run.score.distance.mean, h);
}

// A method that throws, or a back-end that does not exist, is a failure of that hole, with the
// message; the next method on the same hole runs as if nothing had happened.
TEST(RunMethodOnHole, AFailingMethodIsAFailureOfThatHoleOnly) {
  const BenchmarkMethod thrower{"thrower",
                                [](const Mesh&, int, const ImagesCallback&) -> RepairResult {
                                  throw std::runtime_error("boom");
                                }};
  const HoleRun failed = run_on_flat_hole(thrower);
  EXPECT_FALSE(failed.score.filled);
  EXPECT_EQ(failed.score.failure, "error: boom");
  EXPECT_DOUBLE_EQ(failed.score.area, flat_hole().punched.holes[0].area);
  EXPECT_EQ(failed.score.distance.hausdorff, 0);

  try {
    make_filler("plane:no-such-back-end");
    ADD_FAILURE() << "an unknown back-end made a filler";
  } catch (const InvalidInput& error) {
    EXPECT_NE(std::string(error.what()).find("no-such-back-end"), std::string::npos);
  }

  const HoleRun next = run_on_flat_hole(truth_method(0));
  EXPECT_TRUE(next.score.filled);
  EXPECT_NEAR(next.score.distance.hausdorff, 0, 1e-12);
}

// Our pipeline with a back-end fills the flat hole on a plane, flat (harmonic restores a plane
// exactly), and hands over the hole's range image: depth, labels with hole pixels, the restoration.
TEST(RunMethodOnHole, PipelineMethodFillsAndShowsItsImage) {
  const HoleRun run = run_on_flat_hole(
      pipeline_method("harmonic", testing::paper_chain(testing::plane_options("harmonic"))));
  EXPECT_TRUE(run.score.filled) << run.score.failure;
  EXPECT_EQ(run.score.method, "plane");
  EXPECT_LT(run.score.distance.hausdorff, 1e-6);
  EXPECT_GT(run.score.new_faces, 0);
  EXPECT_EQ(run.patch.face_count(), run.score.new_faces);
  ASSERT_FALSE(run.depth.empty());
  EXPECT_EQ(run.labels.size(), run.depth.size());
  EXPECT_EQ(run.restored.size(), run.depth.size());
  EXPECT_GT(cv::countNonZero(run.labels == kHolePixel), 20);
  EXPECT_EQ(run_on_flat_hole(baseline_method({})).score.method, "cgal-fair");
}

// punched_loops maps each punched hole of a sphere to its own loop.
TEST(PunchedLoops, EachHoleHasItsLoop) {
  const Mesh sphere = testing::make_sphere(16);
  PunchOptions options;
  options.max_radius = 5;
  const PunchResult punched = punch_holes(sphere, options);
  ASSERT_EQ(punched.holes.size(), 5u);
  std::vector<int> loops = punched_loops(sphere, punched);
  std::sort(loops.begin(), loops.end());
  EXPECT_EQ(loops, (std::vector<int>{0, 1, 2, 3, 4}));
}

// Table 3's positions: lowest error first, ties share the better position, failures (NaN) share
// the last; a hole every method failed on is not ranked; a tolerance makes near ties ties.
TEST(RankPositions, RanksHandMadeErrors) {
  const std::vector<std::vector<double>> errors = {
      {1, 2, 2, kNan}, {kNan, kNan, kNan, kNan}, {0.5, 0.2, 0.3, 0.1}};
  EXPECT_EQ(rank_positions(errors),
            (std::vector<std::vector<int>>{{1, 2, 2, 4}, {}, {4, 2, 3, 1}}));
  EXPECT_EQ(rank_positions(errors, 0.15),
            (std::vector<std::vector<int>>{{1, 2, 2, 4}, {}, {4, 1, 2, 1}}));
  EXPECT_THROW(rank_positions({{1, 2}, {1}}), InvalidInput);
  EXPECT_THROW(rank_positions(errors, -1), InvalidInput);
}

// Shares of each position over the ranked holes of a class (the unranked one is left out).
TEST(RankShares, CountsPositionsOverRankedHoles) {
  const std::vector<std::vector<int>> positions = {{1, 2, 2, 4}, {}, {4, 2, 3, 1}};
  const std::vector<std::vector<double>> shares = rank_shares(positions, {0, 1, 2}, 4);
  EXPECT_EQ(shares, (std::vector<std::vector<double>>{
                        {0.5, 0, 0, 0.5}, {0, 1, 0, 0}, {0, 0.5, 0.5, 0}, {0.5, 0, 0, 0.5}}));
  EXPECT_EQ(rank_shares(positions, {2}, 4)[0], (std::vector<double>{0, 0, 0, 1}));
  EXPECT_EQ(rank_shares(positions, {1}, 4)[0], (std::vector<double>{0, 0, 0, 0}));
}

// Table 4's coefficient on series with known answers.
TEST(Pearson, KnownCoefficients) {
  EXPECT_NEAR(pearson({1, 2, 3, 4}, {1, 3, 2, 4}), 0.8, 1e-15);
  EXPECT_NEAR(pearson({1, 2, 3}, {3, 5, 7}), 1, 1e-15);
  EXPECT_NEAR(pearson({1, 2, 3}, {-1, -2, -3}), -1, 1e-15);
  EXPECT_TRUE(std::isnan(pearson({1, 2, 3}, {2, 2, 2})));
  EXPECT_TRUE(std::isnan(pearson({1}, {2})));
  EXPECT_THROW(pearson({1, 2}, {1}), InvalidInput);
}

// Table 5's classes: equal widths from the smallest value to the largest, the largest in the last.
TEST(EqualWidthClasses, SplitsTheRange) {
  const EqualWidthClasses classes = equal_width_classes({0, 1, 2.5, 10, 7.4}, 4);
  EXPECT_EQ(classes.edges, (std::vector<double>{0, 2.5, 5, 7.5, 10}));
  EXPECT_EQ(classes.of_value, (std::vector<int>{0, 0, 1, 3, 2}));
  EXPECT_EQ(equal_width_classes({3, 3}, 10).of_value, (std::vector<int>{0, 0}));
  EXPECT_THROW(equal_width_classes({1}, 0), InvalidInput);
  EXPECT_THROW(equal_width_classes({1, kNan}, 2), InvalidInput);
}

// Table 8's mean ± sample standard deviation.
TEST(MeanSd, SampleStatistics) {
  const MeanSd r = mean_sd({1, 2, 3, 4});
  EXPECT_DOUBLE_EQ(r.mean, 2.5);
  EXPECT_DOUBLE_EQ(r.sd, std::sqrt(5.0 / 3));
  EXPECT_EQ(r.count, 4);
  EXPECT_EQ(mean_sd({7}).mean, 7);
  EXPECT_EQ(mean_sd({7}).sd, 0);
  EXPECT_EQ(mean_sd({}).count, 0);
}

}  // namespace
}  // namespace rangefill
