#include "bench_report.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

#include "cli.h"
#include "rangefill/eval/metrics.h"
#include "report_scripts.h"
#include "svg.h"

namespace rangefill::cli {

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

struct Table {
  std::string title;  // with the paper's table it mirrors
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<int> row_holes = {};  // in HTML, each row's first cell opens this hole (when given)
};

std::string fixed(double value, int digits = 2) {
  if (std::isnan(value)) return "—";
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

// A p-value: three decimals, or two significant digits below 0.001.
std::string p_value(double p) {
  if (std::isnan(p) || p >= 0.001) return fixed(p, 3);
  char text[32];
  std::snprintf(text, sizeof text, "%.1e", p);
  return text;
}

std::string percent(double share) {
  return fixed(100 * share, 1) + " %";
}

std::string ordinal(int n) {
  const char* suffix = n % 10 == 1 && n % 100 != 11   ? "st"
                       : n % 10 == 2 && n % 100 != 12 ? "nd"
                       : n % 10 == 3 && n % 100 != 13 ? "rd"
                                                      : "th";
  return std::to_string(n) + suffix;
}

std::vector<std::string> position_names(size_t methods) {
  std::vector<std::string> names;
  for (size_t p = 1; p <= methods; ++p) names.push_back(ordinal(static_cast<int>(p)));
  return names;
}

double area_in_dm2(const BenchHole& hole) {
  return hole.hole.area / (hole.mean_edge * hole.mean_edge);
}

// H / d_m of a run, NaN when the hole stayed open.
double hausdorff_in_dm(const BenchResults& results, size_t hole, size_t method) {
  const BenchRun& run = results.runs[hole][method];
  return run.score.filled ? run.score.distance.hausdorff / results.holes[hole].mean_edge : kNan;
}

// Whether two or more back-ends all filled hole h, by the same strategy, with patches at the same
// distance from the truth (the same patch: the strategy did not use the back-end).
bool filled_alike(const BenchResults& results, size_t h) {
  if (results.backends < 2) return false;
  const BenchRun& first = results.runs[h][0];
  for (int m = 0; m < results.backends; ++m) {
    const BenchRun& run = results.runs[h][m];
    if (!run.score.filled || run.score.method != first.score.method ||
        run.score.distance.hausdorff != first.score.distance.hausdorff ||
        run.score.distance.mean != first.score.distance.mean) {
      return false;
    }
  }
  return true;
}

// H / d_m of each hole for method m, +inf where it did not close the hole.
std::vector<double> hausdorff_or_failure(const BenchResults& results, size_t m) {
  std::vector<double> values;
  for (size_t h = 0; h < results.holes.size(); ++h) {
    const double value = hausdorff_in_dm(results, h, m);
    values.push_back(std::isnan(value) ? std::numeric_limits<double>::infinity() : value);
  }
  return values;
}

ClassRanking ranking(const std::string& name, const std::string& label, std::vector<int> holes,
                     const std::vector<std::vector<int>>& positions, size_t methods) {
  ClassRanking ranked{name, label, std::move(holes), {}};
  ranked.shares = rank_shares(positions, ranked.holes, static_cast<int>(methods));
  return ranked;
}

// Rows "method | 1st | 2nd | ..." of one ranking.
void add_share_rows(const BenchResults& results, const ClassRanking& ranking,
                    const std::vector<std::string>& lead, Table& table) {
  for (size_t m = 0; m < results.methods.size(); ++m) {
    std::vector<std::string> row = lead;
    row.push_back(results.methods[m]);
    for (double share : ranking.shares[m]) row.push_back(percent(share));
    table.rows.push_back(std::move(row));
  }
}

// Holes of a class that some method filled (those the ranking counts).
int ranked_holes(const std::vector<std::vector<int>>& positions, const ClassRanking& ranking) {
  int count = 0;
  for (int h : ranking.holes) count += !positions[h].empty();
  return count;
}

int ranked_holes(const BenchSummary& summary, const ClassRanking& ranking) {
  return ranked_holes(summary.positions, ranking);
}

// Table 3's layout: per method its share of first places with their bootstrap interval, then the
// share of each position.
Table ranking_table(const std::string& title, const std::vector<std::string>& methods,
                    const ClassRanking& ranking, const std::vector<Interval>& first_intervals) {
  Table table{title, {"method", "1st: 95 % CI"}, {}};
  for (const std::string& name : position_names(methods.size())) table.header.push_back(name);
  for (size_t m = 0; m < methods.size(); ++m) {
    const Interval& interval = first_intervals[m];
    std::vector<std::string> row = {methods[m], std::isnan(interval.low)
                                                    ? "—"
                                                    : fixed(100 * interval.low, 0) + "–" +
                                                          fixed(100 * interval.high, 0) + " %"};
    for (double share : ranking.shares[m]) row.push_back(percent(share));
    table.rows.push_back(std::move(row));
  }
  return table;
}

// Table 5 (or its curvature counterpart): class, holes, method, shares of each position.
Table class_table(const std::string& title, const std::string& class_header,
                  const BenchResults& results, const BenchSummary& summary,
                  const std::vector<ClassRanking>& classes) {
  Table table{title, {class_header, "holes", "method"}, {}};
  for (const std::string& name : position_names(results.methods.size()))
    table.header.push_back(name);
  for (const ClassRanking& ranking : classes) {
    add_share_rows(results, ranking, {ranking.name, std::to_string(ranked_holes(summary, ranking))},
                   table);
  }
  return table;
}

// Share of first places by class, a column per class.
Table first_place_table(const std::string& title, const BenchResults& results,
                        const BenchSummary& summary, const std::vector<ClassRanking>& classes) {
  Table table{title, {"method"}, {}};
  for (const ClassRanking& ranking : classes) {
    table.header.push_back(ranking.name + " (" + std::to_string(ranked_holes(summary, ranking)) +
                           ")");
  }
  for (size_t m = 0; m < results.methods.size(); ++m) {
    std::vector<std::string> row = {results.methods[m]};
    for (const ClassRanking& ranking : classes) row.push_back(percent(ranking.shares[m][0]));
    table.rows.push_back(std::move(row));
  }
  return table;
}

}  // namespace

std::string base64(const std::string& data) {
  static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto bytes = [&](size_t i) { return static_cast<unsigned>(static_cast<uchar>(data[i])); };
  std::string text;
  for (size_t i = 0; i < data.size(); i += 3) {
    const unsigned n = bytes(i) << 16 | (i + 1 < data.size() ? bytes(i + 1) << 8 : 0) |
                       (i + 2 < data.size() ? bytes(i + 2) : 0);
    text += digits[n >> 18 & 63];
    text += digits[n >> 12 & 63];
    text += i + 1 < data.size() ? digits[n >> 6 & 63] : '=';
    text += i + 2 < data.size() ? digits[n & 63] : '=';
  }
  return text;
}

std::vector<ClassRanking> surface_classes(const BenchSummary& summary) {
  std::vector<ClassRanking> both = summary.curvature_classes;
  both.insert(both.end(), summary.feature_classes.begin(), summary.feature_classes.end());
  return both;
}

namespace {

std::vector<Table> tables(const BenchResults& results, const BenchSummary& summary) {
  std::vector<Table> all;
  const size_t n = results.holes.size();
  Table overview{
      "Per method (" + std::to_string(summary.meshes) + " meshes, " + std::to_string(n) +
          " holes; medians over the holes each method closed, with bootstrap 95 % intervals; "
          "Wilcoxon's signed-rank test of H against the best median's method on every hole, a "
          "hole left open counting as the worst)",
      {"method", "holes closed", "meshes closed", "H median / d_m [95 % CI]",
       "H median / d_m: low, medium, high curvature", "H max / d_m", "mean dist / d_m (mean)",
       "r = edge / d_m", "smallest angle", "self-intersections", "vs best: p (pairs)",
       "s / hole (median)"},
      {}};
  for (size_t m = 0; m < results.methods.size(); ++m) {
    const MethodSummary& s = summary.methods[m];
    const std::string test =
        static_cast<int>(m) == summary.best
            ? "best"
            : (std::isnan(s.versus_best.p) ? std::string("—") : p_value(s.versus_best.p)) + " (" +
                  std::to_string(s.versus_best.pairs) + ")";
    overview.rows.push_back(
        {results.methods[m], std::to_string(s.filled) + " / " + std::to_string(n),
         std::to_string(s.closed_meshes) + " / " + std::to_string(summary.meshes),
         fixed(s.hausdorff_median) + " [" + fixed(s.hausdorff_median_interval.low) + ", " +
             fixed(s.hausdorff_median_interval.high) + "]",
         fixed(s.hausdorff_median_by_curvature[0]) + ", " +
             fixed(s.hausdorff_median_by_curvature[1]) + ", " +
             fixed(s.hausdorff_median_by_curvature[2]),
         fixed(s.hausdorff_max), fixed(s.mean_distance_mean),
         fixed(s.edge_ratio.mean) + " ± " + fixed(s.edge_ratio.sd),
         fixed(s.smallest_angle, 1) + "°", std::to_string(s.self_intersections), test,
         fixed(s.seconds_median, 3)});
  }
  all.push_back(std::move(overview));

  const std::string alike_note =
      summary.alike_holes > 0 ? "; every back-end filled " + std::to_string(summary.alike_holes) +
                                    " of them alike (ties among the back-ends)"
                              : "";
  all.push_back(ranking_table("Effectiveness ranking by H, " +
                                  std::to_string(ranked_holes(summary, summary.overall)) +
                                  " holes some method closed" + alike_note + " (Table 3)",
                              results.methods, summary.overall, summary.share_intervals[0]));
  if (results.backends >= 2) {
    const std::vector<std::string> backends(results.methods.begin(),
                                            results.methods.begin() + results.backends);
    all.push_back(ranking_table(
        "The back-ends ranked among themselves, on the " +
            std::to_string(ranked_holes(summary.backend_positions, summary.backends)) +
            " holes where their fills differ (" + std::to_string(summary.alike_holes) +
            " filled alike by every back-end left out)",
        backends, summary.backends, summary.backend_first_share_intervals));
  }

  Table chosen{
      "Where the band test chose the image pipeline (repair --select): each method's H "
      "median / d_m on the holes where the row's back-end filled the hole",
      {"back-end", "holes"},
      {}};
  for (const std::string& method : results.methods) chosen.header.push_back(method);
  for (size_t m = 0; m < results.methods.size(); ++m) {
    const MethodSummary& s = summary.methods[m];
    if (s.chosen_holes.empty()) continue;
    std::vector<std::string> row = {results.methods[m], std::to_string(s.chosen_holes.size())};
    for (double value : s.hausdorff_median_where_chosen) row.push_back(fixed(value, 3));
    chosen.rows.push_back(std::move(row));
  }
  if (!chosen.rows.empty()) all.push_back(std::move(chosen));

  Table correlation{
      "Pearson correlation of H / d_m with area / d_m² (Table 4) and edge ratio "
      "(Table 8), over the holes each method closed",
      {"method", "PCC", "holes", "r mean ± sd"},
      {}};
  for (size_t m = 0; m < results.methods.size(); ++m) {
    const MethodSummary& s = summary.methods[m];
    correlation.rows.push_back({results.methods[m], fixed(s.pearson),
                                std::to_string(s.pearson_holes),
                                fixed(s.edge_ratio.mean) + " ± " + fixed(s.edge_ratio.sd)});
  }
  all.push_back(std::move(correlation));

  all.push_back(first_place_table("First places by hole-area class (area / d_m², holes ranked)",
                                  results, summary, summary.area_classes));
  all.push_back(
      first_place_table("First places by curvature class and sharp feature (holes ranked)", results,
                        summary, surface_classes(summary)));
  all.push_back(class_table("Effectiveness ranking by hole-area class (Table 5)", "area / d_m²",
                            results, summary, summary.area_classes));
  all.push_back(class_table("Effectiveness ranking by curvature class", "curvature", results,
                            summary, summary.curvature_classes));
  all.push_back(class_table("Effectiveness ranking with and without sharp features", "feature",
                            results, summary, summary.feature_classes));

  Table holes{
      "H / d_m of every hole and the strategy that filled it (Tables 1 and 2; open: not "
      "closed)",
      {"mesh", "hole", "shape", "radius / d_m", "length / d_m", "area / d_m²", "bending",
       "curvature", "sharp", "back-ends alike"},
      {}};
  for (const std::string& method : results.methods) holes.header.push_back(method);
  for (size_t h = 0; h < n; ++h) {
    const BenchHole& hole = results.holes[h];
    std::vector<std::string> row = {hole.mesh,
                                    std::to_string(hole.index),
                                    shape_name(hole.hole.shape),
                                    fixed(hole.hole.radius / hole.mean_edge, 1),
                                    fixed(hole.hole.length / hole.mean_edge, 1),
                                    fixed(area_in_dm2(hole), 0),
                                    fixed(hole.hole.bending),
                                    curvature_name(hole.hole.curvature),
                                    hole.hole.sharp_feature ? "yes" : "no",
                                    summary.alike[h] ? "yes" : "no"};
    for (size_t m = 0; m < results.methods.size(); ++m) {
      const double value = hausdorff_in_dm(results, h, m);
      row.push_back(
          std::isnan(value) ? "open" : fixed(value) + " (" + results.runs[h][m].score.method + ")");
    }
    holes.rows.push_back(std::move(row));
    holes.row_holes.push_back(static_cast<int>(h));
  }
  all.push_back(std::move(holes));
  return all;
}

std::string to_markdown(const Table& table) {
  std::ostringstream md;
  md << "### " << table.title << "\n\n|";
  for (const std::string& cell : table.header) md << ' ' << cell << " |";
  md << "\n|";
  for (size_t c = 0; c < table.header.size(); ++c) md << (c == 0 ? "---|" : "---:|");
  md << '\n';
  for (const auto& row : table.rows) {
    md << '|';
    for (const std::string& cell : row) md << ' ' << cell << " |";
    md << '\n';
  }
  md << '\n';
  return md.str();
}

std::string to_html(const Table& table) {
  std::ostringstream html;
  html << "<h3>" << escape_xml(table.title) << "</h3>\n<table>\n<tr>";
  for (const std::string& cell : table.header) html << "<th>" << escape_xml(cell) << "</th>";
  html << "</tr>\n";
  for (size_t r = 0; r < table.rows.size(); ++r) {
    html << "<tr>";
    for (size_t c = 0; c < table.rows[r].size(); ++c) {
      const std::string cell = escape_xml(table.rows[r][c]);
      if (c == 0 && r < table.row_holes.size()) {
        const std::string hole = std::to_string(table.row_holes[r]);
        html << "<td><a href=\"#hole-" << hole << "\" data-hole=\"" << hole << "\">" << cell
             << "</a></td>";
      } else {
        html << "<td>" << cell << "</td>";
      }
    }
    html << "</tr>\n";
  }
  html << "</table>\n";
  return html.str();
}

// A depth image of a hole; report.js colours it by its `kind` (depth, mask, restored, or
// difference-source: a restoration shown as its difference from the first).
std::string image(const std::string& png, const std::string& kind, const std::string& caption) {
  return "<figure><img class=\"depth\" data-kind=\"" + kind + "\" src=\"data:image/png;base64," +
         png + "\" alt=\"" + escape_xml(caption) + "\"><figcaption>" + escape_xml(caption) +
         "</figcaption></figure>\n";
}

// One hole of the gallery: its description, its 3D view's button, its images and every method's
// outcome.
std::string hole_section(const BenchResults& results, size_t h) {
  const BenchHole& hole = results.holes[h];
  std::ostringstream html;
  html << "<section class=\"hole\" id=\"hole-" << h << "\"><h3>" << escape_xml(hole.mesh)
       << ", hole " << hole.index << " <button data-hole=\"" << h << "\">3D view</button></h3>\n<p>"
       << shape_name(hole.hole.shape) << ", " << fixed(area_in_dm2(hole), 0)
       << " d<sub>m</sub>², bending " << fixed(hole.hole.bending) << " ("
       << curvature_name(hole.hole.curvature) << " curvature"
       << (hole.hole.sharp_feature ? ", on a sharp feature" : "") << ")</p>\n<div class=\"row\">";
  std::string first;  // the method of the first restoration
  for (size_t m = 0; m < results.methods.size(); ++m) {
    const BenchRun& run = results.runs[h][m];
    if (run.depth_png.empty()) continue;
    const double value = hausdorff_in_dm(results, h, m);
    const std::string caption =
        results.methods[m] + ": H " + (std::isnan(value) ? "open" : fixed(value) + " d_m");
    if (first.empty()) {
      html << image(run.depth_png, "depth", "range image (unknown: black)")
           << image(run.mask_png, "mask", "mask") << image(run.restored_png, "restored", caption);
      first = results.methods[m];
    } else {
      html << image(run.restored_png, "restored", caption)
           << image(run.restored_png, "difference-source",
                    results.methods[m] + " − " + first + " (blue below, red above)");
    }
  }
  if (first.empty()) html << "<p>No range image: no method inpainted this hole.</p>";
  html << "</div>\n<table><tr><th>method</th><th>H / d_m</th><th>filled by</th><th>new "
          "faces</th><th>failure</th></tr>\n";
  for (size_t m = 0; m < results.methods.size(); ++m) {
    const BenchRun& run = results.runs[h][m];
    html << "<tr><td>" << escape_xml(results.methods[m]) << "</td><td>"
         << fixed(hausdorff_in_dm(results, h, m)) << "</td><td>" << escape_xml(run.score.method)
         << "</td><td>" << run.score.new_faces << "</td><td>" << escape_xml(run.score.failure)
         << "</td></tr>\n";
  }
  html << "</table></section>\n";
  return html.str();
}

// The bytes of `values` (little-endian on the machines we build for), base64.
template <typename Value>
std::string base64_of(const std::vector<Value>& values) {
  return base64(
      std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(Value)));
}

// A mesh for report.js: positions as float32 relative to `centre`, triangles as uint32.
nlohmann::json view_mesh_json(const Mesh& mesh, const Vec3& centre) {
  std::vector<float> positions;
  for (const Vec3& p : mesh.positions) {
    for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(p[k] - centre[k]));
  }
  std::vector<std::uint32_t> triangles;
  for (const Triangle& t : mesh.triangles) triangles.insert(triangles.end(), t.begin(), t.end());
  return {{"p", base64_of(positions)}, {"t", base64_of(triangles)}};
}

// What report.js draws: per hole its surroundings, its truth and each method's patch with the
// distance of each patch vertex to the truth in d_m, on a scale shared by the methods.
nlohmann::json views_json(const BenchResults& results, const BenchSummary& summary) {
  nlohmann::json holes = nlohmann::json::array();
  for (size_t h = 0; h < results.views.size(); ++h) {
    const HoleView& view = results.views[h];
    const double d_m = results.holes[h].mean_edge;
    Vec3 centre = Vec3::Zero();
    for (const Vec3& p : view.truth.positions) centre += p;
    centre /= std::max<double>(1, view.truth.positions.size());
    std::vector<int> truth_faces(view.truth.face_count());
    std::iota(truth_faces.begin(), truth_faces.end(), 0);
    double scale = 0;
    nlohmann::json methods = nlohmann::json::array();
    for (size_t m = 0; m < results.methods.size(); ++m) {
      const BenchRun& run = results.runs[h][m];
      nlohmann::json method = {{"name", results.methods[m]},
                               {"h", fixed(hausdorff_in_dm(results, h, m))},
                               {"patch", nullptr}};
      if (run.score.filled && !run.patch.triangles.empty() && !truth_faces.empty()) {
        std::vector<float> distances;
        for (double d : distances_to_faces(run.patch.positions, view.truth, truth_faces)) {
          distances.push_back(static_cast<float>(d / d_m));
          scale = std::max(scale, d / d_m);
        }
        method["patch"] = view_mesh_json(run.patch, centre);
        method["d"] = base64_of(distances);
      }
      methods.push_back(method);
    }
    // Shown first: the method ranked first on the hole (else the first).
    int best = 0;
    const std::vector<int>& positions = summary.positions[h];
    for (size_t m = 0; m < positions.size(); ++m) {
      if (positions[m] < positions[best]) best = static_cast<int>(m);
    }
    holes.push_back(
        {{"title", results.holes[h].mesh + ", hole " + std::to_string(results.holes[h].index)},
         {"scale", std::max(scale, 1e-9)},
         {"best", best},
         {"surroundings", view_mesh_json(view.surroundings, centre)},
         {"truth", view_mesh_json(view.truth, centre)},
         {"methods", methods}});
  }
  return {{"holes", holes}};
}

// A number, or null for NaN (JSON has no NaN).
nlohmann::json number_or_null(double value) {
  return std::isnan(value) ? nlohmann::json(nullptr) : nlohmann::json(value);
}

nlohmann::json interval_json(const Interval& interval) {
  return {number_or_null(interval.low), number_or_null(interval.high)};
}

// Method m's intervals of the shares of each position, first to last.
nlohmann::json rank_share_intervals_json(const BenchSummary& summary, size_t m) {
  nlohmann::json intervals = nlohmann::json::array();
  for (const std::vector<Interval>& position : summary.share_intervals) {
    intervals.push_back(interval_json(position[m]));
  }
  return intervals;
}

// The back-ends' ranking among themselves (null with fewer than two).
nlohmann::json backends_json(const BenchResults& results, const BenchSummary& summary) {
  if (results.backends < 2) return nullptr;
  nlohmann::json shares = nlohmann::json::object(), intervals = nlohmann::json::object();
  for (int m = 0; m < results.backends; ++m) {
    shares[results.methods[m]] = summary.backends.shares[m];
    intervals[results.methods[m]] = interval_json(summary.backend_first_share_intervals[m]);
  }
  return {{"holes", ranked_holes(summary.backend_positions, summary.backends)},
          {"shares", shares},
          {"first_share_ci95", intervals}};
}

nlohmann::json shares_json(const BenchResults& results, const ClassRanking& ranking) {
  nlohmann::json shares = nlohmann::json::object();
  for (size_t m = 0; m < results.methods.size(); ++m)
    shares[results.methods[m]] = ranking.shares[m];
  return {{"class", ranking.name}, {"holes", ranking.holes.size()}, {"shares", shares}};
}

}  // namespace

BenchSummary summarize(const BenchResults& results, int area_classes, double tie) {
  const size_t methods = results.methods.size(), n = results.holes.size();
  BenchSummary summary;
  std::vector<std::vector<double>> errors(n, std::vector<double>(methods));
  for (size_t h = 0; h < n; ++h) {
    for (size_t m = 0; m < methods; ++m) errors[h][m] = hausdorff_in_dm(results, h, m);
    summary.alike.push_back(filled_alike(results, h));
    summary.alike_holes += summary.alike.back();
  }
  summary.positions = rank_positions(errors, tie);
  std::vector<int> all(n), different;
  for (size_t h = 0; h < n; ++h) {
    all[h] = static_cast<int>(h);
    if (!summary.alike[h]) different.push_back(static_cast<int>(h));
  }
  summary.overall = ranking("all", "all", all, summary.positions, methods);
  for (size_t position = 1; position <= methods; ++position) {
    summary.share_intervals.push_back(bootstrap_share_intervals(
        summary.positions, all, static_cast<int>(methods), static_cast<int>(position)));
  }
  if (results.backends >= 2) {
    std::vector<std::vector<double>> backend_errors;
    for (const std::vector<double>& row : errors) {
      backend_errors.emplace_back(row.begin(), row.begin() + results.backends);
    }
    summary.backend_positions = rank_positions(backend_errors, tie);
    summary.backends =
        ranking("back-ends", "back-ends", different, summary.backend_positions, results.backends);
    summary.backend_first_share_intervals =
        bootstrap_share_intervals(summary.backend_positions, different, results.backends);
  }

  std::map<std::string, std::vector<size_t>> holes_of_mesh;
  for (size_t h = 0; h < n; ++h) holes_of_mesh[results.holes[h].mesh].push_back(h);
  summary.meshes = static_cast<int>(holes_of_mesh.size());
  for (size_t m = 0; m < methods; ++m) {
    MethodSummary s;
    std::vector<double> hausdorff, mean_distance, seconds, edge_ratio, area;
    std::array<std::vector<double>, 3> hausdorff_by_curvature;
    for (size_t h = 0; h < n; ++h) {
      const BenchRun& run = results.runs[h][m];
      s.self_intersections += run.self_intersections;
      if (!run.score.filled) continue;
      const double d_m = results.holes[h].mean_edge;
      ++s.filled;
      hausdorff.push_back(run.score.distance.hausdorff / d_m);
      mean_distance.push_back(run.score.distance.mean / d_m);
      seconds.push_back(run.score.seconds);
      edge_ratio.push_back(run.score.edge_ratio);
      hausdorff_by_curvature[static_cast<int>(results.holes[h].hole.curvature)].push_back(
          hausdorff.back());
      s.smallest_angle = std::min(s.smallest_angle, run.score.smallest_angle);
      area.push_back(area_in_dm2(results.holes[h]));
    }
    for (const auto& [mesh, holes] : holes_of_mesh) {
      bool closed = true;
      for (size_t h : holes) {
        const BenchRun& run = results.runs[h][m];
        closed &= run.score.filled && run.manifold && run.self_intersections == 0;
      }
      s.closed_meshes += closed;
    }
    s.hausdorff_median = median(hausdorff);
    s.hausdorff_median_interval = bootstrap_median_interval(hausdorff);
    s.hausdorff_max = hausdorff.empty() ? 0 : *std::max_element(hausdorff.begin(), hausdorff.end());
    s.mean_distance_mean = mean_sd(mean_distance).mean;
    for (int c = 0; c < 3; ++c) {
      s.hausdorff_median_by_curvature[c] =
          hausdorff_by_curvature[c].empty() ? kNan : median(hausdorff_by_curvature[c]);
    }
    s.seconds_median = median(seconds);
    s.edge_ratio = mean_sd(edge_ratio);
    s.pearson = pearson(area, hausdorff);
    s.pearson_holes = static_cast<int>(hausdorff.size());
    summary.methods.push_back(s);
  }
  for (size_t m = 1; m < methods; ++m) {
    const MethodSummary &candidate = summary.methods[m], &best = summary.methods[summary.best];
    if (candidate.filled > 0 &&
        (best.filled == 0 || candidate.hausdorff_median < best.hausdorff_median)) {
      summary.best = static_cast<int>(m);
    }
  }
  for (size_t m = 0; m < methods; ++m) {
    MethodSummary& s = summary.methods[m];
    for (size_t h = 0; h < n; ++h) {
      if (results.runs[h][m].score.selected.rfind("plane", 0) == 0) {
        s.chosen_holes.push_back(static_cast<int>(h));
      }
    }
    if (s.chosen_holes.empty()) continue;
    for (size_t other = 0; other < methods; ++other) {
      std::vector<double> hausdorff;
      for (int h : s.chosen_holes) {
        const double value = hausdorff_in_dm(results, h, other);
        if (!std::isnan(value)) hausdorff.push_back(value);
      }
      s.hausdorff_median_where_chosen.push_back(hausdorff.empty() ? kNan : median(hausdorff));
    }
  }
  const std::vector<double> best_errors = hausdorff_or_failure(results, summary.best);
  for (size_t m = 0; m < methods; ++m) {
    summary.methods[m].versus_best =
        wilcoxon_signed_rank(hausdorff_or_failure(results, m), best_errors);
  }

  auto members_where = [&](auto member) {
    std::vector<int> members;
    for (size_t h = 0; h < n; ++h) {
      if (member(h)) members.push_back(static_cast<int>(h));
    }
    return members;
  };
  std::vector<double> areas;
  for (const BenchHole& hole : results.holes) areas.push_back(area_in_dm2(hole));
  const EqualWidthClasses classes = equal_width_classes(areas, area_classes);
  for (int c = 0; c < area_classes; ++c) {
    ClassRanking ranked = ranking(fixed(classes.edges[c], 0) + "–" + fixed(classes.edges[c + 1], 0),
                                  fixed(classes.edges[c], 0) + "–" + fixed(classes.edges[c + 1], 0),
                                  members_where([&](size_t h) { return classes.of_value[h] == c; }),
                                  summary.positions, methods);
    if (ranked_holes(summary, ranked) > 0) summary.area_classes.push_back(std::move(ranked));
  }
  for (CurvatureClass curvature :
       {CurvatureClass::low, CurvatureClass::medium, CurvatureClass::high}) {
    ClassRanking ranked = ranking(
        curvature_name(curvature), curvature_name(curvature),
        members_where([&](size_t h) { return results.holes[h].hole.curvature == curvature; }),
        summary.positions, methods);
    if (ranked_holes(summary, ranked) > 0) summary.curvature_classes.push_back(std::move(ranked));
  }
  for (bool sharp : {true, false}) {
    ClassRanking ranked = ranking(
        sharp ? "sharp feature" : "no sharp feature", sharp ? "sharp" : "no sharp",
        members_where([&](size_t h) { return results.holes[h].hole.sharp_feature == sharp; }),
        summary.positions, methods);
    if (ranked_holes(summary, ranked) > 0) summary.feature_classes.push_back(std::move(ranked));
  }
  return summary;
}

nlohmann::json summary_json(const BenchResults& results, const BenchSummary& summary) {
  nlohmann::json methods = nlohmann::json::object();
  for (size_t m = 0; m < results.methods.size(); ++m) {
    const MethodSummary& s = summary.methods[m];
    methods[results.methods[m]] = {
        {"holes", results.holes.size()},
        {"filled", s.filled},
        {"meshes", summary.meshes},
        {"closed_meshes", s.closed_meshes},
        {"self_intersections", s.self_intersections},
        {"hausdorff_median", s.hausdorff_median},
        {"hausdorff_max", s.hausdorff_max},
        {"mean_distance_mean", s.mean_distance_mean},
        {"hausdorff_median_by_curvature",
         {{"low", s.hausdorff_median_by_curvature[0]},
          {"medium", s.hausdorff_median_by_curvature[1]},
          {"high", s.hausdorff_median_by_curvature[2]}}},
        {"smallest_angle_deg", s.smallest_angle},
        {"edge_ratio_mean", s.edge_ratio.mean},
        {"edge_ratio_sd", s.edge_ratio.sd},
        {"pearson_hausdorff_area", s.pearson},
        {"pearson_holes", s.pearson_holes},
        {"seconds_per_hole_median", s.seconds_median},
        {"image_pipeline_chosen",
         {{"holes", s.chosen_holes},
          {"hausdorff_median_by_method", s.hausdorff_median_where_chosen}}},
        {"rank_shares", summary.overall.shares[m]},
        {"hausdorff_median_ci95", interval_json(s.hausdorff_median_interval)},
        {"rank_shares_ci95", rank_share_intervals_json(summary, m)},
        {"versus_best",
         {{"method", results.methods[summary.best]},
          {"test", "Wilcoxon signed-rank, two-sided"},
          {"pairs", s.versus_best.pairs},
          {"statistic", s.versus_best.statistic},
          {"p", number_or_null(s.versus_best.p)},
          {"exact", s.versus_best.exact}}}};
  }
  auto class_list = [&](const std::vector<ClassRanking>& classes) {
    nlohmann::json list = nlohmann::json::array();
    for (const ClassRanking& ranking : classes) list.push_back(shares_json(results, ranking));
    return list;
  };
  nlohmann::json holes = nlohmann::json::array();
  for (size_t h = 0; h < results.holes.size(); ++h) {
    const BenchHole& hole = results.holes[h];
    holes.push_back({{"mesh", hole.mesh},
                     {"hole", hole.index},
                     {"shape", shape_name(hole.hole.shape)},
                     {"area_dm2", area_in_dm2(hole)},
                     {"bending", hole.hole.bending},
                     {"curvature", curvature_name(hole.hole.curvature)},
                     {"sharp_feature", hole.hole.sharp_feature},
                     {"alike_for_every_backend", static_cast<bool>(summary.alike[h])},
                     {"positions", summary.positions[h]}});
  }
  return {{"methods", methods},
          {"method_order", results.methods},
          {"best", results.methods[summary.best]},
          {"ranked_holes", ranked_holes(summary, summary.overall)},
          {"holes_alike_for_every_backend", summary.alike_holes},
          {"backends_among_themselves", backends_json(results, summary)},
          {"ranking",
           {{"all", shares_json(results, summary.overall)},
            {"area_classes", class_list(summary.area_classes)},
            {"curvature_classes", class_list(summary.curvature_classes)},
            {"feature_classes", class_list(summary.feature_classes)}}},
          {"holes", holes}};
}

std::string markdown_tables(const BenchResults& results, const BenchSummary& summary) {
  std::string md;
  for (const Table& table : tables(results, summary)) md += to_markdown(table);
  return md;
}

std::string hausdorff_area_svg(const BenchResults& results) {
  std::vector<ScatterSeries> panels;
  for (size_t m = 0; m < results.methods.size(); ++m) {
    ScatterSeries panel{results.methods[m], {}, {}};
    for (size_t h = 0; h < results.holes.size(); ++h) {
      const double value = hausdorff_in_dm(results, h, m);
      if (std::isnan(value)) continue;
      panel.x.push_back(area_in_dm2(results.holes[h]));
      panel.y.push_back(value);
    }
    panels.push_back(std::move(panel));
  }
  return scatter_svg(panels, "hole area / d_m²", "Hausdorff distance / d_m");
}

std::string class_ranking_svg(const BenchResults& results, const std::vector<ClassRanking>& classes,
                              const std::string& class_label) {
  std::vector<BarPanel> panels;
  for (size_t m = 0; m < results.methods.size(); ++m) {
    BarPanel panel{results.methods[m], {}, {}};
    for (size_t c = 0; c < classes.size(); ++c) {
      panel.categories.push_back(classes[c].label);
      panel.segments.push_back(classes[c].shares[m]);
    }
    panels.push_back(std::move(panel));
  }
  return stacked_bars_svg(panels, position_names(results.methods.size()), class_label);
}

std::string html_report(const BenchResults& results, const BenchSummary& summary,
                        const std::string& command, double tie) {
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
          "<title>rangefill bench</title>\n"
          // First of all: the page's errors counted where the browser test reads them.
          "<script>window.reportErrors=0;function reportError(){++window.reportErrors;"
          "if(document.body)document.body.dataset.errors=window.reportErrors;}"
          "window.addEventListener('error',reportError);"
          "window.addEventListener('unhandledrejection',reportError);"
          "const consoleError=console.error;console.error=function(...a){reportError();"
          "consoleError.apply(console,a);};</script>\n<style>\n"
          "body{font-family:sans-serif;margin:2em;max-width:1400px}\n"
          "table{border-collapse:collapse;margin:0.5em 0 1.5em}\n"
          "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}\n"
          "td:first-child,th:first-child{text-align:left}\n"
          ".row{display:flex;flex-wrap:wrap;gap:10px}\n"
          "figure{margin:0;width:220px}figcaption{font-size:80%;text-align:center}\n"
          ".depth{width:220px;image-rendering:pixelated;border:1px solid #ccc}\n"
          ".hole{border-top:1px solid #999;margin-top:1em}\n"
          "#viewer{position:fixed;right:12px;bottom:12px;width:480px;background:#fff;"
          "border:1px solid #888;box-shadow:0 2px 8px #0004;font-size:85%;z-index:10}\n"
          "#viewer.closed .canvas,#viewer.closed .methods,#viewer.closed .legend{display:none}\n"
          "#viewer .bar{display:flex;gap:8px;align-items:center;padding:4px;background:#eee}\n"
          "#viewer .title{flex:1}#viewer .canvas{width:480px;height:360px}\n"
          "#viewer .methods button.on{font-weight:bold;background:#cde}\n"
          "#viewer .legend{display:flex;gap:6px;align-items:center;padding:4px}\n"
          "#viewer .legend-bar{flex:1;height:10px}\n"
          "</style></head><body>\n<h1>rangefill bench</h1>\n<p><code>"
       << escape_xml(command)
       << "</code></p>\n<p>H: symmetric Hausdorff distance between each patch and the faces "
          "removed (Pérez et al., Section X); a method that did not close a hole is ranked last "
          "on it; distances within "
       << fixed(tie, 3)
       << " d_m of each other share the better place. Click a hole (in the last table or its "
          "section) for its 3D view: the surroundings in grey, the faces removed (the ground "
          "truth) as a black wireframe, each method's patch coloured by its distance to the "
          "truth.</p>\n"
          "<div id=\"viewer\" class=\"closed\"><div class=\"bar\"><span class=\"title\">3D "
          "view</span><label><input type=\"checkbox\" id=\"viewer-truth\" checked> ground "
          "truth</label><button class=\"close\">show / hide</button></div>"
          "<div class=\"canvas\"></div><div class=\"methods\"></div><div class=\"legend\">"
          "distance to the truth: 0<span class=\"legend-bar\"></span><span "
          "class=\"legend-high\"></span></div></div>\n";
  const std::vector<Table> all = tables(results, summary);
  for (size_t t = 0; t + 1 < all.size(); ++t) html << to_html(all[t]);
  html << "<h2>Plots</h2>\n<h3>Hausdorff distance against hole area, every method</h3>\n"
       << hausdorff_area_svg(results) << "<h3>Positions by hole-area class</h3>\n"
       << class_ranking_svg(results, summary.area_classes, "hole area / d_m²")
       << "<h3>Positions by curvature class and sharp feature</h3>\n"
       << class_ranking_svg(results, surface_classes(summary), "curvature class, sharp feature")
       << "<h2>Holes</h2>\n"
       << to_html(all.back())
       << "<p>Each hole's range image (normalised depth of the first plane tried, in the viridis "
          "colour map, unknown pixels black), its mask, each back-end's restoration in the same "
          "colour map and, for the second back-end on, its difference from the first "
          "restoration.</p>\n";
  for (size_t h = 0; h < results.holes.size(); ++h) html << hole_section(results, h);
  html << "<script type=\"application/json\" id=\"bench-views\">"
       << views_json(results, summary).dump() << "</script>\n<script>" << kThreeJs
       << "</script>\n<script>" << kOrbitControlsJs << "</script>\n<script>" << kReportJs
       << "</script>\n</body></html>\n";
  return html.str();
}

}  // namespace rangefill::cli
