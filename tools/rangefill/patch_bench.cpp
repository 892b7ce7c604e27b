// rangefill patch-bench: the back-ends on depth patches cut from meshes as the pipeline sees them
// (the held-out meshes of train-foe by default), with blob holes; RMSE at the holes in d_m.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>

#include "cli.h"
#include "rangefill/eval/patches.h"
#include "rangefill/inpaint/inpainters.h"
#include "research.h"

namespace rangefill::cli {

namespace {

namespace fs = std::filesystem;

struct PatchBenchCommand {
  std::vector<std::string> meshes;
  std::string only = kValidationMeshes, inpainters = "foe,foe:roth-black,ns,telea,harmonic", csv;
  HoleSampleOptions samples;
  InpainterOptions inpainting;
  bool json = false;
};

struct PatchRow {
  std::string mesh;
  int patch;
  double masked_share;
  std::vector<double> rmse, seconds;  // per back-end
};

// One row per patch: its mesh, index, masked share, and each back-end's RMSE and seconds.
std::string csv_rows(const std::vector<std::string>& names, const std::vector<PatchRow>& rows) {
  std::ostringstream csv;
  csv << "mesh,patch,masked_share";
  for (const std::string& name : names) csv << ',' << name << "_rmse," << name << "_s";
  csv << '\n';
  for (const PatchRow& row : rows) {
    csv << row.mesh << ',' << row.patch << ',' << row.masked_share;
    for (size_t m = 0; m < names.size(); ++m) csv << ',' << row.rmse[m] << ',' << row.seconds[m];
    csv << '\n';
  }
  return csv.str();
}

int run_patch_bench(const PatchBenchCommand& command) {
  const std::vector<std::string> names = split_list(command.inpainters);
  if (names.empty()) throw UsageError("--inpainters: no back-end given");
  std::vector<std::unique_ptr<Inpainter>> inpainters;
  for (const std::string& name : names) {
    check_inpainter(name, "--inpainters");
    inpainters.push_back(make_inpainter(name, command.inpainting));
  }
  const std::vector<std::string> only = split_list(command.only);
  std::vector<PatchRow> rows;
  const bool progress = stderr_is_terminal();
  for (const fs::path& file : mesh_files(command.meshes)) {
    const std::string name = file.filename().string();
    if (!only.empty() && std::count(only.begin(), only.end(), name) == 0) continue;
    const std::vector<HoleSample> samples =
        hole_samples(load_mesh(file.string()), name, command.samples);
    for (size_t p = 0; p < samples.size(); ++p) {
      if (progress)
        std::fprintf(stderr, "\r\033[K%s: patch %zu/%zu", name.c_str(), p + 1, samples.size());
      PatchRow row{name,
                   static_cast<int>(p),
                   cv::countNonZero(samples[p].mask) / double(samples[p].mask.total()),
                   {},
                   {}};
      for (const std::unique_ptr<Inpainter>& inpainter : inpainters) {
        const auto start = std::chrono::steady_clock::now();
        row.rmse.push_back(restoration_rmse(samples[p], *inpainter));
        row.seconds.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      }
      rows.push_back(row);
    }
  }
  if (progress) std::fprintf(stderr, "\r\033[K");
  if (rows.empty()) throw UsageError("--meshes: no patches (check --only and the mesh files)");

  if (!command.csv.empty()) write_file_atomically(csv_rows(names, rows), command.csv);

  // Per back-end: median and mean RMSE, the share of patches it restores best, and the share of
  // patches on which the first back-end beats it (the paired comparison).
  nlohmann::json report = nlohmann::json::object();
  if (!command.json) {
    std::printf("%zu patches of %dx%d pixels, holes %.0f-%.0f%% (seed %llu); RMSE in d_m\n",
                rows.size(), command.samples.patches.size, command.samples.patches.size,
                100 * command.samples.min_hole, 100 * command.samples.max_hole,
                static_cast<unsigned long long>(command.samples.patches.seed));
    std::printf("%-22s %11s %11s %8s %12s %10s\n", "back-end", "RMSE median", "RMSE mean", "best",
                ("vs " + names[0]).c_str(), "ms median");
  }
  for (size_t m = 0; m < names.size(); ++m) {
    std::vector<double> rmse, milliseconds;
    int best = 0, beaten_by_first = 0;
    for (const PatchRow& row : rows) {
      rmse.push_back(row.rmse[m]);
      milliseconds.push_back(1000 * row.seconds[m]);
      best += *std::min_element(row.rmse.begin(), row.rmse.end()) == row.rmse[m];
      beaten_by_first += row.rmse[0] < row.rmse[m];
    }
    double mean = 0;
    for (double value : rmse) mean += value / rmse.size();
    const double best_share = double(best) / rows.size();
    const double first_wins = double(beaten_by_first) / rows.size();
    if (command.json) {
      report[names[m]] = {{"patches", rows.size()},
                          {"rmse_median", median(rmse)},
                          {"rmse_mean", mean},
                          {"best_share", best_share},
                          {"beaten_by_first", first_wins},
                          {"ms_median", median(milliseconds)}};
      continue;
    }
    std::printf("%-22s %11.4f %11.4f %7.0f%% %11.0f%% %10.2f\n", names[m].c_str(), median(rmse),
                mean, 100 * best_share, 100 * first_wins, median(milliseconds));
  }
  if (command.json) print_json(report);
  return kOk;
}

}  // namespace

void add_patch_bench_command(CLI::App& app, Runner& runner) {
  auto command = std::make_shared<PatchBenchCommand>();
  CLI::App* sub = app.add_subcommand(
      "patch-bench", "Score back-ends on depth patches cut from meshes, with blob holes");
  sub->add_option("--meshes", command->meshes, "Meshes, or directories of them")->required();
  sub->add_option("--only", command->only,
                  "File names of the meshes to use, comma-separated (empty: all)")
      ->capture_default_str();
  sub->add_option("--inpainters", command->inpainters,
                  "Comma-separated back-ends; the first is compared with each")
      ->capture_default_str();
  add_patch_options(sub, command->samples);
  add_foe_inference_options(sub, command->inpainting);
  sub->add_option("--csv", command->csv, "Write one row per patch to this file");
  sub->add_flag("--json", command->json, "Print the summary as JSON");
  sub->callback([command, &runner] { runner = [command] { return run_patch_bench(*command); }; });
}

}  // namespace rangefill::cli
