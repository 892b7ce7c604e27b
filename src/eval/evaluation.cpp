#include "rangefill/eval/evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include "rangefill/core/errors.h"
#include "rangefill/hole/holes.h"
#include "rangefill/image/plane_filler.h"

namespace rangefill {

namespace {

// Punched hole of each input vertex on a removed face (holes are apart, so at most one), else -1.
std::vector<int> holes_by_vertex(const Mesh& original, const PunchResult& punched) {
  std::vector<int> hole(original.vertex_count(), -1);
  for (size_t h = 0; h < punched.holes.size(); ++h) {
    for (int face : punched.holes[h].removed_faces) {
      for (int v : original.triangles[face]) hole[v] = static_cast<int>(h);
    }
  }
  return hole;
}

}  // namespace

std::vector<int> punched_loops(const Mesh& original, const PunchResult& punched) {
  const std::vector<int> hole = holes_by_vertex(original, punched);
  std::vector<int> loop_of_hole(punched.holes.size(), -1);
  for (const BoundaryLoop& loop : find_holes(punched.mesh, build_topology(punched.mesh)).loops) {
    const int h = hole[punched.original_vertex[loop.vertices.front()]];
    if (h >= 0) loop_of_hole[h] = loop.id;
  }
  return loop_of_hole;
}

std::vector<HoleScore> score_repair(const Mesh& original, const PunchResult& punched,
                                    const RepairResult& repaired, double mean_edge) {
  const std::vector<int> hole_of_vertex = holes_by_vertex(original, punched);
  const HoleSet loops = find_holes(punched.mesh, build_topology(punched.mesh));
  std::vector<HoleScore> scores(punched.holes.size());
  for (size_t h = 0; h < scores.size(); ++h) {
    scores[h].hole = static_cast<int>(h);
    scores[h].failure = "not attempted";
    for (int face : punched.holes[h].removed_faces)
      scores[h].area += 0.5 * triangle_cross(original, face).norm();
  }
  for (const HoleReport& report : repaired.holes) {
    if (report.pass != 0) continue;
    const int first = loops.loops.at(report.loop).vertices.front();
    const int h = hole_of_vertex[punched.original_vertex[first]];
    if (h < 0) continue;
    HoleScore& score = scores[h];
    score.filled = report.filled;  // until a loop of it is found open below
    score.failure = report.failure;
    score.new_vertices = report.new_vertices;
    score.new_faces = report.new_faces;
    score.seconds = report.seconds;
    score.method = report.method;
    score.selected = report.selected;
    score.zone_faces = report.zone_faces;
    score.steps = report.steps;
    if (!report.filled) continue;
    const std::vector<int> patch = faces_of_hole(repaired.mesh, report.id);
    score.distance = surface_distance(repaired.mesh, patch, original,
                                      punched.holes[h].removed_faces, mean_edge / 4);
    score.edge_ratio = mean_edge_length(repaired.mesh, patch) / mean_edge;
    score.smallest_angle = smallest_angle_degrees(repaired.mesh, patch);
  }
  // A hole partly filled (Section VI-C) whose rest stayed open is not filled.
  for (const BoundaryLoop& loop : find_holes(repaired.mesh, build_topology(repaired.mesh)).loops) {
    for (int v : loop.vertices) {
      if (v >= punched.mesh.vertex_count()) continue;
      const int h = hole_of_vertex[punched.original_vertex[v]];
      if (h < 0 || !scores[h].filled) continue;
      scores[h].filled = false;
      scores[h].failure =
          "partly filled; a loop of " + std::to_string(loop.vertices.size()) + " edges stays open";
    }
  }
  return scores;
}

BenchmarkMethod pipeline_method(const std::string& name, RepairOptions options) {
  options.threads = 1;
  return {name, [options](const Mesh& mesh, int loop, const ImagesCallback& on_images) {
            RepairOptions for_loop = options;
            for_loop.holes = {loop};
            for_loop.on_images = on_images;
            return repair(mesh, for_loop);
          }};
}

BenchmarkMethod baseline_method(const BaselineOptions& options) {
  return {baseline_name(options.method),
          [options](const Mesh& mesh, int loop, const ImagesCallback&) {
            BaselineOptions for_loop = options;
            for_loop.holes = {loop};
            return fill_holes_cgal(mesh, for_loop);
          }};
}

HoleRun run_method_on_hole(const Mesh& original, const PunchResult& punched, int hole, int loop,
                           const BenchmarkMethod& method, double mean_edge) {
  if (hole < 0 || hole >= static_cast<int>(punched.holes.size())) {
    throw InvalidInput("benchmark: there is no punched hole " + std::to_string(hole));
  }
  if (loop < 0)
    throw InvalidInput("benchmark: punched hole " + std::to_string(hole) + " has no loop");
  HoleRun run;
  run.score.hole = hole;
  run.score.area = punched.holes[hole].area;
  const auto start = std::chrono::steady_clock::now();
  try {
    const RepairResult repaired = method.fill(punched.mesh, loop, [&run](const HoleImages& images) {
      if (!run.depth.empty()) return;
      run.depth = images.image.depth.clone();
      run.labels = images.image.labels.clone();
      run.restored = images.restored.clone();
    });
    run.score = score_repair(original, punched, repaired, mean_edge).at(hole);
    const std::vector<int> generated = faces_of_hole(repaired.mesh, kAnyHole);
    run.self_intersections = count_self_intersections(repaired.mesh, generated);
    run.patch = extract_faces(repaired.mesh, generated);
    const ManifoldCheck check = check_manifold(repaired.mesh);
    run.manifold = check.nonmanifold_edges == 0 && check.misoriented_edges == 0 &&
                   check.nonmanifold_vertices == 0;
  } catch (const std::exception& error) {
    run.score.filled = false;
    run.score.failure = std::string("error: ") + error.what();
  } catch (...) {
    run.score.filled = false;
    run.score.failure = "error: an exception that is not a std::exception";
  }
  run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

std::vector<std::vector<int>> rank_positions(const std::vector<std::vector<double>>& errors,
                                             double tolerance) {
  if (!(tolerance >= 0)) throw InvalidInput("ranking: the tolerance must not be negative");
  std::vector<std::vector<int>> positions;
  for (const std::vector<double>& row : errors) {
    if (row.size() != errors.front().size()) {
      throw InvalidInput("ranking: every hole needs an error for each method");
    }
    std::vector<double> succeeded;
    for (double e : row) {
      if (!std::isnan(e)) succeeded.push_back(e);
    }
    std::vector<int> position;
    if (!succeeded.empty()) {
      std::sort(succeeded.begin(), succeeded.end());
      for (double e : row) {
        const auto better = std::lower_bound(succeeded.begin(), succeeded.end(), e - tolerance);
        position.push_back(std::isnan(e) ? static_cast<int>(succeeded.size()) + 1
                                         : 1 + static_cast<int>(better - succeeded.begin()));
      }
    }
    positions.push_back(std::move(position));
  }
  return positions;
}

std::vector<std::vector<double>> rank_shares(const std::vector<std::vector<int>>& positions,
                                             const std::vector<int>& holes, int methods) {
  std::vector<std::vector<double>> shares(methods, std::vector<double>(methods, 0.0));
  int ranked = 0;
  for (int h : holes) {
    const std::vector<int>& row = positions.at(h);
    if (row.empty()) continue;
    if (static_cast<int>(row.size()) != methods) {
      throw InvalidInput("ranking: hole " + std::to_string(h) + " has another number of methods");
    }
    ++ranked;
    for (int m = 0; m < methods; ++m) shares[m][row[m] - 1] += 1;
  }
  if (ranked == 0) return shares;
  for (std::vector<double>& row : shares) {
    for (double& share : row) share /= ranked;
  }
  return shares;
}

double pearson(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size()) throw InvalidInput("pearson: the series differ in length");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (x.size() < 2) return nan;
  const double n = static_cast<double>(x.size());
  const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n;
  const double my = std::accumulate(y.begin(), y.end(), 0.0) / n;
  double sxy = 0, sxx = 0, syy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (!(sxx > 0 && syy > 0)) return nan;
  return sxy / std::sqrt(sxx * syy);
}

EqualWidthClasses equal_width_classes(const std::vector<double>& values, int count) {
  if (count < 1) throw InvalidInput("classes: at least one class is needed");
  for (double v : values) {
    if (!std::isfinite(v)) throw InvalidInput("classes: a value is not finite");
  }
  EqualWidthClasses classes;
  const double low = values.empty() ? 0 : *std::min_element(values.begin(), values.end());
  const double high = values.empty() ? 0 : *std::max_element(values.begin(), values.end());
  const double width = (high - low) / count;
  for (int c = 0; c <= count; ++c) classes.edges.push_back(c == count ? high : low + c * width);
  for (double v : values) {
    const int c = width > 0 ? static_cast<int>((v - low) / width) : 0;
    classes.of_value.push_back(std::min(c, count - 1));
  }
  return classes;
}

MeanSd mean_sd(const std::vector<double>& values) {
  MeanSd result;
  result.count = static_cast<int>(values.size());
  if (values.empty()) return result;
  result.mean = std::accumulate(values.begin(), values.end(), 0.0) / values.size();
  if (values.size() < 2) return result;
  double squares = 0;
  for (double v : values) squares += (v - result.mean) * (v - result.mean);
  result.sd = std::sqrt(squares / (values.size() - 1));
  return result;
}

}  // namespace rangefill
