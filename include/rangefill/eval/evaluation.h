// Scoring a repair against ground truth, the faces punched out of a closed mesh, and the
// aggregates of Pérez et al., Section X (effectiveness ranking, Pearson correlation with hole area,
// ranking by classes, edge ratio).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rangefill/eval/baselines.h"
#include "rangefill/eval/metrics.h"
#include "rangefill/eval/punch.h"
#include "rangefill/repair/pipeline.h"

namespace rangefill {

/// How well one punched hole was restored, distances in world units.
struct HoleScore {
  int hole = 0;         // index in PunchResult::holes
  double area = 0;      // area of the removed faces
  bool filled = false;  // closed: no boundary loop of the result runs along it
  std::string failure;
  SurfaceDistance distance;   // first = the patch, second = the removed faces
  double edge_ratio = 0;      // mean patch edge / d_m
  double smallest_angle = 0;  // of the patch's faces, in degrees
  int new_vertices = 0;
  int new_faces = 0;
  double seconds = 0;
  std::string method;    // of the pass-0 fill (HoleReport::method)
  std::string selected;  // the candidate whose band test won (HoleReport::selected), if any
  int zone_faces = 0;
  std::vector<StepSeconds> steps;  // HoleReport::steps
};

/// Scores a repair of `punched.mesh` against the faces removed from `original`: each punched hole
/// is matched to the report of the loop it left, its patch to the generated faces with that
/// report's id. Distances are sampled at spacing d_m / 4. Holes the repair did not attempt count as
/// not filled.
std::vector<HoleScore> score_repair(const Mesh& original, const PunchResult& punched,
                                    const RepairResult& repaired, double mean_edge);

/// Per punched hole, the id (find_holes' numbering) of the boundary loop of punched.mesh it left,
/// or -1 if none runs along it.
std::vector<int> punched_loops(const Mesh& original, const PunchResult& punched);

/// What the benchmark compares: our pipeline with one back-end, or a baseline.
struct BenchmarkMethod {
  std::string name;
  /// Fills the loop with id `loop` of `mesh` and returns the repair, its generated elements marked
  /// as repair() marks them; may call `on_images` as RepairOptions::on_images.
  std::function<RepairResult(const Mesh& mesh, int loop, const ImagesCallback& on_images)> fill;
};

/// repair() with `options`, on the one loop (options.holes and on_images set per call, one thread).
BenchmarkMethod pipeline_method(const std::string& name, RepairOptions options);
/// fill_holes_cgal() with `options`, on the one loop; named by baseline_name.
BenchmarkMethod baseline_method(const BaselineOptions& options);

/// One method on one punched hole.
struct HoleRun {
  HoleScore score;             // failure "error: ..." when the method threw
  int self_intersections = 0;  // pairs of a generated face and another face that intersect
  bool manifold = false;       // the repair has no non-manifold or misoriented element
  double wall_seconds = 0;     // the whole call, the method's set-up included
  Mesh patch;                  // the generated faces, as a mesh of their own (extract_faces)
  /// The first range image inpainted for the hole (RepairOptions::on_images): normalised depth,
  /// pixel labels and the restored depth; empty when there was none (baselines, the front).
  cv::Mat depth, labels, restored;
};

/// Runs `method` on punched hole `hole` of `punched`, whose loop is `loop` (punched_loops), and
/// scores the repair against the faces removed from `original` (score_repair) with d_m
/// `mean_edge`. Whatever the method throws is caught: the hole then counts as not filled, the
/// message its failure, so that one method failing on one hole stops nothing else. Throws
/// InvalidInput if `hole` or `loop` is out of range.
HoleRun run_method_on_hole(const Mesh& original, const PunchResult& punched, int hole, int loop,
                           const BenchmarkMethod& method, double mean_edge);

/// Table 3: each method's position on each hole by its error, 1 for the lowest.
/// errors[hole][method] is NaN where the method failed. Errors within `tolerance` of each other
/// count as equal: a method's position is 1 + the number of methods whose error is lower by more
/// than `tolerance` (so exact ties share the better position: 1, 2, 2, 4); failures share the
/// position after the last success. A hole on which every method failed gets an empty row. Throws
/// InvalidInput if the rows differ in length or the tolerance is negative.
std::vector<std::vector<int>> rank_positions(const std::vector<std::vector<double>>& errors,
                                             double tolerance = 0);

/// Tables 3 and 5: shares[method][p] is the fraction of the ranked holes among `holes` (indices
/// into `positions`; holes with an empty row are left out) on which the method took position
/// p + 1. All zero when no hole is ranked.
std::vector<std::vector<double>> rank_shares(const std::vector<std::vector<int>>& positions,
                                             const std::vector<int>& holes, int methods);

/// Table 4: Pearson's correlation coefficient of x and y; NaN for fewer than two pairs or a
/// constant series. Throws InvalidInput if the sizes differ.
double pearson(const std::vector<double>& x, const std::vector<double>& y);

/// Table 5: `count` classes of equal width from the smallest value to the largest.
struct EqualWidthClasses {
  std::vector<double> edges;  // count + 1 bounds, ascending
  std::vector<int> of_value;  // class of each value; the largest in the last; all 0 when equal
};
/// Throws InvalidInput for count < 1 or a value that is not finite.
EqualWidthClasses equal_width_classes(const std::vector<double>& values, int count);

/// Table 8: mean and sample standard deviation (0 for fewer than two values; both 0 for none).
struct MeanSd {
  double mean = 0, sd = 0;
  int count = 0;
};
MeanSd mean_sd(const std::vector<double>& values);

}  // namespace rangefill
