// What `rangefill bench` measured and how it is reported: the aggregates of Pérez et al., Section
// X (computed by the library, evaluation.h) as a JSON summary, Markdown tables, SVG plots and one
// self-contained HTML report.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rangefill/eval/evaluation.h"
#include "rangefill/eval/statistics.h"

namespace rangefill::cli {

/// One punched hole of the benchmark.
struct BenchHole {
  std::string mesh;      // file name
  int index = 0;         // in its mesh's PunchResult
  double mean_edge = 0;  // d_m of its mesh
  PunchedHole hole;      // removed_faces left out
};

/// What the report's 3D view of a hole shows besides the patches: the surface round the hole
/// (faces of the punched mesh near it) and the faces punched out (the ground truth).
struct HoleView {
  Mesh surroundings, truth;
};

/// One method on one hole, as it came back from its child process.
struct BenchRun {
  HoleScore score;
  int self_intersections = 0;
  bool manifold = false;
  double wall_seconds = 0;
  std::string depth_png, mask_png, restored_png;  // base64; empty without a range image
  Mesh patch;                                     // the generated faces (with --out or --save)
};

struct BenchResults {
  std::vector<std::string> methods;  // the back-ends of the pipeline first, then the baselines
  int backends = 0;                  // how many of `methods` are back-ends
  std::vector<BenchHole> holes;
  std::vector<std::vector<BenchRun>> runs;  // [hole][method]
  std::vector<HoleView> views;              // per hole, with --out
};

/// The ranking within one class of holes.
struct ClassRanking {
  std::string name;
  std::string label;                        // short, for plots
  std::vector<int> holes;                   // indices into BenchResults::holes
  std::vector<std::vector<double>> shares;  // [method][position − 1]
};

struct MethodSummary {
  int filled = 0, closed_meshes = 0, self_intersections = 0;
  double hausdorff_median = 0, hausdorff_max = 0;  // over d_m
  double mean_distance_mean = 0;                   // over d_m, the mean over the filled holes
  std::array<double, 3> hausdorff_median_by_curvature{};  // low, medium, high (NaN: no hole)
  double smallest_angle = 180;         // degrees, over the patches of the filled holes
  Interval hausdorff_median_interval;  // bootstrap, 95 %, over the holes it filled
  SignedRankTest versus_best;  // H against the best method's on every hole (a failure: +inf)
  double seconds_median = 0;
  MeanSd edge_ratio;   // Table 8, over the filled holes
  double pearson = 0;  // Table 4: of H / d_m with area / d_m², over the filled holes (NaN: none)
  int pearson_holes = 0;
  std::vector<int> chosen_holes;  // where the band test chose this method's image pipeline
  std::vector<double> hausdorff_median_where_chosen;  // each method's on chosen_holes, / d_m
};

struct BenchSummary {
  int meshes = 0;
  std::vector<MethodSummary> methods;
  int best = 0;  // the method of the lowest H median (over the holes it filled)
  /// Bootstrap 95 % intervals of the overall ranking's shares, [position − 1][method].
  std::vector<std::vector<Interval>> share_intervals;
  /// Per hole: every back-end filled it by the same strategy with the same patch (there are two
  /// or more); such holes are left out of the back-ends' ranking among themselves, where they
  /// would only be ties.
  std::vector<bool> alike;
  int alike_holes = 0;
  std::vector<std::vector<int>> backend_positions;  // [hole][back-end], among the back-ends
  ClassRanking backends;                            // over the holes not filled alike
  std::vector<Interval> backend_first_share_intervals;
  std::vector<std::vector<int>> positions;  // [hole][method], rank_positions of H
  ClassRanking overall;                     // Table 3
  std::vector<ClassRanking> area_classes;   // Table 5
  std::vector<ClassRanking> curvature_classes, feature_classes;
};

/// The curvature classes, then the feature classes.
std::vector<ClassRanking> surface_classes(const BenchSummary& summary);

/// The aggregates, with `area_classes` classes of equal width in area / d_m² (those without a
/// ranked hole left out); values of H within `tie`·d_m of each other rank as equal.
BenchSummary summarize(const BenchResults& results, int area_classes, double tie);

nlohmann::json summary_json(const BenchResults& results, const BenchSummary& summary);

/// `data` in base64.
std::string base64(const std::string& data);

/// Every table of the summary as Markdown, each under a heading naming the paper's table.
std::string markdown_tables(const BenchResults& results, const BenchSummary& summary);

/// H / d_m against area / d_m², the methods overlaid.
std::string hausdorff_area_svg(const BenchResults& results);

/// Shares of the positions by class (named along `class_label`), one panel per method.
std::string class_ranking_svg(const BenchResults& results, const std::vector<ClassRanking>& classes,
                              const std::string& class_label);

/// One self-contained page: the tables, the plots and, for each hole, a 3D view (three.js: the
/// surroundings, the truth and each method's patch coloured by its distance to the truth), its
/// range image, mask and each back-end's restoration; `tie` as for summarize.
std::string html_report(const BenchResults& results, const BenchSummary& summary,
                        const std::string& command, double tie);

}  // namespace rangefill::cli
