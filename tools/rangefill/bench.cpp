// rangefill bench: punch holes into closed meshes, repair them with each back-end, and measure.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <numeric>
#include <sstream>

#include "cli.h"
#include "rangefill/errors.h"
#include "rangefill/evaluation.h"
#include "rangefill/pipeline.h"
#include "rangefill/punch.h"

namespace rangefill::cli {

namespace {

namespace fs = std::filesystem;

struct BenchCommand {
  std::vector<std::string> meshes;
  std::string inpainters, trends = "quadric", csv, save, filler = "plane";
  std::string fallback = "front,least-area";
  PunchOptions punch;
  InpainterOptions inpainting;
  int threads = 1;
  bool json = false;
};

struct Row {
  std::string mesh, method;
  HoleScore score;
  double mean_edge;
};

struct MethodSummary {
  int holes = 0, filled = 0, meshes = 0, closed_meshes = 0, self_intersections = 0;
  std::vector<double> hausdorff, mean_distance, edge_ratio, seconds;
};

int run_bench(const BenchCommand& command) {
  std::vector<std::string> inpainters = split_list(command.inpainters);
  if (inpainters.empty()) inpainters = inpainter_names();
  std::vector<TrendKind> trends;
  for (const std::string& name : split_list(command.trends))
    trends.push_back(trend_from_name(name));
  for (const std::string& name : inpainters) check_inpainter(name, "--inpainters");
  const std::vector<fs::path> files = mesh_files(command.meshes);
  if (files.empty()) throw UsageError("--meshes: no mesh files found");

  std::vector<Row> rows;
  std::map<std::string, MethodSummary> summaries;
  std::vector<std::string> methods;
  const bool progress = stderr_is_terminal();
  for (const fs::path& file : files) {
    const Mesh original = load_mesh(file.string());
    const double mean_edge = mean_edge_length(original);
    PunchOptions punch = command.punch;
    punch.seed = seed_for_mesh(command.punch.seed, file.filename().string());
    const PunchResult punched = punch_holes(original, punch);
    const std::string stem = file.stem().string();
    if (!command.save.empty()) {
      fs::create_directories(command.save);
      write_mesh(punched.mesh, fs::path(command.save) / (stem + "-punched.ply"));
      Mesh truth;  // the removed faces, each marked with the hole it belongs to
      for (size_t h = 0; h < punched.holes.size(); ++h) {
        const Mesh part = extract_faces(original, punched.holes[h].removed_faces);
        const int offset = truth.vertex_count();
        for (const Vec3& p : part.positions) add_vertex(truth, p, static_cast<int>(h));
        for (Triangle t : part.triangles) {
          for (int& v : t) v += offset;
          add_face(truth, t, static_cast<int>(h));
        }
      }
      write_mesh(truth, fs::path(command.save) / (stem + "-truth.ply"));
    }
    for (const std::string& inpainter : inpainters) {
      for (TrendKind trend : trends) {
        const std::string method = inpainter + (trends.size() > 1 ? "+" + trend_name(trend) : "");
        if (std::find(methods.begin(), methods.end(), method) == methods.end())
          methods.push_back(method);
        if (progress)
          std::fprintf(stderr, "\r\033[K%s: %s", file.filename().c_str(), method.c_str());
        RepairOptions options;
        options.inpainter = inpainter;
        options.inpainting = command.inpainting;
        options.trend = trend;
        options.threads = command.threads;
        options.filler = command.filler == "front" ? Filler::front : Filler::plane;
        set_fallbacks(command.fallback, options);
        const RepairResult repaired = repair(punched.mesh, options);
        if (!command.save.empty()) {
          write_mesh(repaired.mesh, fs::path(command.save) / (stem + "-" + method + ".ply"));
        }
        const std::vector<HoleScore> scores = score_repair(original, punched, repaired, mean_edge);
        MethodSummary& summary = summaries[method];
        const int intersections =
            count_self_intersections(repaired.mesh, faces_of_hole(repaired.mesh, kAnyHole));
        ++summary.meshes;
        summary.self_intersections += intersections;
        bool all_filled = true;
        for (const HoleScore& score : scores) {
          rows.push_back({file.filename().string(), method, score, mean_edge});
          ++summary.holes;
          all_filled &= score.filled;
          if (!score.filled) continue;
          ++summary.filled;
          summary.hausdorff.push_back(score.distance.hausdorff / mean_edge);
          summary.mean_distance.push_back(score.distance.mean / mean_edge);
          summary.edge_ratio.push_back(score.edge_ratio);
          summary.seconds.push_back(score.seconds);
        }
        summary.closed_meshes +=
            all_filled && intersections == 0 && check_manifold(repaired.mesh).closed_manifold();
      }
    }
  }
  if (progress) std::fprintf(stderr, "\r\033[K");

  if (!command.csv.empty()) {
    std::ofstream csv(command.csv);
    csv << "mesh,method,hole,area,filled,hausdorff,from_patch,from_truth,mean_distance,d_m,"
           "edge_ratio,new_vertices,new_faces,seconds,filler,zone_faces,zone_s,planes_s,image_s,"
           "inpainting_s,stitching_s,checking_s,front_s,failure\n";
    for (const Row& row : rows) {
      const HoleScore& s = row.score;
      csv << row.mesh << ',' << row.method << ',' << s.hole << ',' << s.area << ',' << s.filled
          << ',' << s.distance.hausdorff << ',' << s.distance.from_first << ','
          << s.distance.from_second << ',' << s.distance.mean << ',' << row.mean_edge << ','
          << s.edge_ratio << ',' << s.new_vertices << ',' << s.new_faces << ',' << s.seconds
          << ",\"" << s.method << "\"," << s.zone_faces << ',' << s.stages.zone << ','
          << s.stages.planes << ',' << s.stages.image << ',' << s.stages.inpainting << ','
          << s.stages.stitching << ',' << s.stages.checking << ',' << s.stages.front << ",\""
          << s.failure << "\"\n";
    }
  }

  nlohmann::json report = nlohmann::json::object();
  if (!command.json) {
    std::printf("%zu meshes, %d holes each asked (seed %llu)\n", files.size(), command.punch.holes,
                static_cast<unsigned long long>(command.punch.seed));
    std::printf("%-16s %6s %6s %8s %9s %9s %9s %13s %7s %10s\n", "method", "holes", "filled",
                "closed", "H med/dm", "H max/dm", "mean/dm", "edge r", "self-x", "s/hole");
  }
  for (const std::string& method : methods) {
    const MethodSummary& s = summaries[method];
    const double r_mean =
        s.edge_ratio.empty()
            ? 0
            : std::accumulate(s.edge_ratio.begin(), s.edge_ratio.end(), 0.0) / s.edge_ratio.size();
    double r_var = 0;
    for (double r : s.edge_ratio) r_var += (r - r_mean) * (r - r_mean);
    const double r_sd = s.edge_ratio.size() > 1 ? std::sqrt(r_var / (s.edge_ratio.size() - 1)) : 0;
    const double h_max =
        s.hausdorff.empty() ? 0 : *std::max_element(s.hausdorff.begin(), s.hausdorff.end());
    if (command.json) {
      report[method] = {{"holes", s.holes},
                        {"filled", s.filled},
                        {"meshes", s.meshes},
                        {"closed_meshes", s.closed_meshes},
                        {"self_intersections", s.self_intersections},
                        {"hausdorff_median", median(s.hausdorff)},
                        {"hausdorff_max", h_max},
                        {"mean_distance_median", median(s.mean_distance)},
                        {"edge_ratio_mean", r_mean},
                        {"edge_ratio_sd", r_sd},
                        {"seconds_per_hole_median", median(s.seconds)}};
      continue;
    }
    char edge[32];
    std::snprintf(edge, sizeof edge, "%.2f ± %.2f", r_mean, r_sd);
    std::printf("%-16s %6d %6d %4d/%-3d %9.3f %9.3f %9.3f %13s %7d %10.4f\n", method.c_str(),
                s.holes, s.filled, s.closed_meshes, s.meshes, median(s.hausdorff), h_max,
                median(s.mean_distance), edge, s.self_intersections, median(s.seconds));
  }
  if (command.json) print_json(report);
  return kOk;
}

}  // namespace

void add_bench_command(CLI::App& app, Runner& runner) {
  auto command = std::make_shared<BenchCommand>();
  CLI::App* sub = app.add_subcommand(
      "bench", "Punch holes into closed meshes, repair them with each back-end, and measure");
  sub->add_option("--meshes", command->meshes, "Closed meshes, or directories of them")->required();
  sub->add_option("--holes-per-mesh", command->punch.holes, "Holes punched per mesh")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  sub->add_option("--seed", command->punch.seed, "Seed of the punching")->capture_default_str();
  sub->add_option("--min-radius", command->punch.min_radius, "Smallest hole radius, in d_m")
      ->capture_default_str();
  sub->add_option("--max-radius", command->punch.max_radius, "Largest hole radius, in d_m")
      ->capture_default_str();
  sub->add_option("--inpainters", command->inpainters, "Comma-separated back-ends (default: all)");
  sub->add_option("--alpha", command->inpainting.mls_alpha,
                  "mls: alpha of the weights exp(-alpha d^2)/d^2 (eq. 6), d in pixels")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  sub->add_option("--trends", command->trends, "Comma-separated trends (none, plane, quadric)")
      ->capture_default_str();
  sub->add_option("--filler", command->filler, "plane or front (see rangefill repair --help)")
      ->capture_default_str()
      ->check(CLI::IsMember({"plane", "front"}));
  sub->add_option("--fallback", command->fallback, "front, least-area, both, or none")
      ->capture_default_str();
  sub->add_option("--threads", command->threads, "Holes filled in parallel")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  sub->add_option("--csv", command->csv, "Write one row per hole and method to this file");
  sub->add_option(
      "--save", command->save,
      "Write each punched mesh, its removed faces (the ground truth) and each repair here");
  sub->add_flag("--json", command->json, "Print the summary as JSON");
  sub->callback([command, &runner] { runner = [command] { return run_bench(*command); }; });
}

}  // namespace rangefill::cli
