// What a script pays, each figure beside a baseline measured in the same run, their ratios printed
// at the end:
// - start-up: `rangefill --version` spawned and waited for, beside `/bin/true` (a process and
//   nothing else);
// - reading: a 1 M-face PLY (a 708 × 708 height-field grid, float positions, written once into a
//   temporary directory), binary and ASCII, by read_mesh, beside read_file of the same bytes (the
//   file system's floor).
// - filling a depth frame (../shared/data/depth-real/livingroom-00000.png, VGA, 40 071 invalid
//   pixels; skipped without ../shared): fill_depth by default, with its colour image and with
//   `fast`, beside
//   cv::inpaint (Navier-Stokes, radius 3) of the same pixels, all on one thread, with the rangefill
//   command's malloc settings.
// - repairing that grid, and one of 2236 × 2236 (10 M faces), with 10 holes punched into it
//   (eval/punch.h, seed 1): repair() with the default options, beside CGAL's
//   triangulate_refine_and_fair_hole of the same loops (fill_holes_cgal, the mesh kit's peer), in
//   this process (I/O aside).
// Report medians: --benchmark_repetitions=9 --benchmark_report_aggregates_only=true.
#include <fcntl.h>
#include <malloc.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/photo.hpp>

#include "rangefill/core/topology.h"
#include "rangefill/depth/fill_depth.h"
#include "rangefill/eval/baselines.h"
#include "rangefill/eval/punch.h"
#include "rangefill/hole/holes.h"
#include "rangefill/io/depth_io.h"
#include "rangefill/io/mesh_io.h"
#include "rangefill/repair/pipeline.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using rangefill::Mesh;

constexpr int kGrid = 708;        // 2 × 708² = 1 002 528 faces
constexpr int kLargeGrid = 2236;  // 2 × 2236² = 9 999 392 faces

// A grid × grid height field, z a gentle wave so that positions are not integers.
Mesh height_field(int grid = kGrid) {
  std::vector<rangefill::Vec3> positions;
  std::vector<rangefill::Triangle> triangles;
  for (int y = 0; y <= grid; ++y) {
    for (int x = 0; x <= grid; ++x) {
      positions.emplace_back(x, y, 5 * std::sin(0.05 * x) * std::cos(0.07 * y));
    }
  }
  const auto id = [grid](int x, int y) { return y * (grid + 1) + x; };
  for (int y = 0; y < grid; ++y) {
    for (int x = 0; x < grid; ++x) {
      triangles.push_back({id(x, y), id(x + 1, y), id(x + 1, y + 1)});
      triangles.push_back({id(x, y), id(x + 1, y + 1), id(x, y + 1)});
    }
  }
  Mesh mesh = rangefill::make_mesh(std::move(positions), std::move(triangles));
  mesh.storage.position = rangefill::ScalarType::float32;
  return mesh;
}

// The two files, written on first use and removed at exit.
struct Files {
  fs::path directory, binary, ascii;
  Files() {
    directory = fs::temp_directory_path() / ("rangefill-bench-process-" + std::to_string(getpid()));
    fs::create_directories(directory);
    binary = directory / "grid-binary.ply";
    ascii = directory / "grid-ascii.ply";
    const Mesh mesh = height_field();
    rangefill::write_mesh(mesh, binary, {rangefill::Encoding::binary});
    rangefill::write_mesh(mesh, ascii, {rangefill::Encoding::ascii});
  }
  ~Files() { fs::remove_all(directory); }
};

const Files& files() {
  static const Files instance;
  return instance;
}

// Spawns the program with its output to /dev/null and waits for it.
void run_process(const char* program, const char* argument, benchmark::State& state) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  char* argv[] = {const_cast<char*>(program), const_cast<char*>(argument), nullptr};
  pid_t pid = 0;
  int status = 0;
  if (posix_spawn(&pid, program, &actions, nullptr, argv, environ) != 0 ||
      waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    state.SkipWithError((std::string("cannot run ") + program).c_str());
  }
  posix_spawn_file_actions_destroy(&actions);
}

void StartUp_True(benchmark::State& state) {
  for (auto _ : state) run_process("/bin/true", nullptr, state);
}

void StartUp_RangefillVersion(benchmark::State& state) {
  for (auto _ : state) run_process(RANGEFILL_BINARY, "--version", state);
}

void read_bytes(benchmark::State& state, const fs::path& path) {
  for (auto _ : state) benchmark::DoNotOptimize(rangefill::read_file(path));
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(fs::file_size(path)));
}

void read_ply(benchmark::State& state, const fs::path& path) {
  for (auto _ : state) benchmark::DoNotOptimize(rangefill::read_mesh(path));
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(fs::file_size(path)));
}

void Read_BinaryBytes(benchmark::State& state) {
  read_bytes(state, files().binary);
}
void Read_BinaryPly(benchmark::State& state) {
  read_ply(state, files().binary);
}
void Read_AsciiBytes(benchmark::State& state) {
  read_bytes(state, files().ascii);
}
void Read_AsciiPly(benchmark::State& state) {
  read_ply(state, files().ascii);
}

// The frame, read on first use; empty without ../shared.
const cv::Mat& frame() {
  static const cv::Mat depth = [] {
    const fs::path path = RANGEFILL_SHARED_DIR "/data/depth-real/livingroom-00000.png";
    return fs::exists(path) ? rangefill::read_depth_image(path) : cv::Mat();
  }();
  return depth;
}

void fill_frame(benchmark::State& state, const rangefill::DepthFillOptions& options) {
  if (frame().empty()) return state.SkipWithError("no ../shared/data/depth-real");
  cv::Mat filled;
  for (auto _ : state) rangefill::fill_depth(frame(), cv::noArray(), filled, options);
}

void Depth_Inpaint(benchmark::State& state) {
  if (frame().empty()) return state.SkipWithError("no ../shared/data/depth-real");
  const cv::Mat invalid = frame() == 0;
  cv::Mat filled;
  for (auto _ : state) cv::inpaint(frame(), invalid, filled, 3, cv::INPAINT_NS);
}

void Depth_FillDefault(benchmark::State& state) {
  fill_frame(state, {});
}

void Depth_FillDefaultColor(benchmark::State& state) {
  const fs::path path = RANGEFILL_SHARED_DIR "/data/depth-real/color/livingroom-00000.jpg";
  if (!fs::exists(path)) return state.SkipWithError("no ../shared/data/depth-real/color");
  rangefill::DepthFillOptions options;
  options.color = rangefill::read_color_image(path);
  fill_frame(state, options);
}

void Depth_FillFast(benchmark::State& state) {
  rangefill::DepthFillOptions options;
  options.fast = true;
  fill_frame(state, options);
}

// A grid with 10 holes punched, and the ids of its loops but the grid's own border.
struct PunchedGrid {
  Mesh mesh;
  std::vector<int> holes;
  explicit PunchedGrid(int grid) {
    rangefill::PunchOptions options;
    options.holes = 10;
    mesh = rangefill::punch_holes(height_field(grid), options).mesh;
    const rangefill::HoleSet loops = rangefill::find_holes(mesh, rangefill::build_topology(mesh));
    for (const rangefill::BoundaryLoop& loop : loops.loops) {
      if (!rangefill::is_border(loop)) holes.push_back(loop.id);
    }
  }
};

// The punched grid of the benchmark's argument, made once.
const PunchedGrid& punched_grid(int grid) {
  static std::map<int, PunchedGrid> grids;
  return grids.try_emplace(grid, grid).first->second;
}

void Repair_Rangefill(benchmark::State& state) {
  const Mesh& mesh = punched_grid(static_cast<int>(state.range(0))).mesh;
  for (auto _ : state) benchmark::DoNotOptimize(rangefill::repair(mesh));
}

void Repair_CgalFair(benchmark::State& state) {
  const PunchedGrid& grid = punched_grid(static_cast<int>(state.range(0)));
  rangefill::BaselineOptions options;
  options.holes = grid.holes;
  for (auto _ : state) benchmark::DoNotOptimize(rangefill::fill_holes_cgal(grid.mesh, options));
}

BENCHMARK(StartUp_True)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(StartUp_RangefillVersion)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(Read_BinaryBytes)->Unit(benchmark::kMillisecond);
BENCHMARK(Read_BinaryPly)->Unit(benchmark::kMillisecond);
BENCHMARK(Read_AsciiBytes)->Unit(benchmark::kMillisecond);
BENCHMARK(Read_AsciiPly)->Unit(benchmark::kMillisecond);
BENCHMARK(Depth_Inpaint)->Unit(benchmark::kMillisecond);
BENCHMARK(Depth_FillDefault)->Unit(benchmark::kMillisecond);
BENCHMARK(Depth_FillDefaultColor)->Unit(benchmark::kMillisecond);
BENCHMARK(Depth_FillFast)->Unit(benchmark::kMillisecond);
BENCHMARK(Repair_Rangefill)
    ->Arg(kGrid)
    ->Arg(kLargeGrid)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(Repair_CgalFair)
    ->Arg(kGrid)
    ->Arg(kLargeGrid)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// The console report, keeping each benchmark's real time (its median when repeated).
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      const std::string name =
          run.run_name.function_name + (run.run_name.args.empty() ? "" : "/" + run.run_name.args);
      if (run.run_type == Run::RT_Aggregate ? run.aggregate_name == "median" : !times.count(name)) {
        times[name] = run.GetAdjustedRealTime();
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, double> times;  // in each benchmark's unit (ms here)
};

}  // namespace

int main(int argc, char** argv) {
  cv::setNumThreads(1);  // cv::inpaint and fill_depth on one thread
  // The rangefill command's malloc settings (tools/rangefill/huge_pages.cpp): freed blocks are
  // kept.
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto ratio = [&](const char* label, const char* measured, const char* baseline) {
    if (reporter.times.count(measured) && reporter.times.count(baseline)) {
      std::printf("%-44s %9.2f ms  %6.2f × %s\n", label, reporter.times[measured],
                  reporter.times[measured] / reporter.times[baseline], baseline);
    }
  };
  ratio("start-up, rangefill --version", "StartUp_RangefillVersion", "StartUp_True");
  ratio("read_mesh, 1 M faces, binary PLY", "Read_BinaryPly", "Read_BinaryBytes");
  ratio("read_mesh, 1 M faces, ASCII PLY", "Read_AsciiPly", "Read_AsciiBytes");
  ratio("fill_depth, VGA frame", "Depth_FillDefault", "Depth_Inpaint");
  ratio("fill_depth with colour, VGA frame", "Depth_FillDefaultColor", "Depth_Inpaint");
  ratio("fill_depth fast, VGA frame", "Depth_FillFast", "Depth_Inpaint");
  ratio("repair, 1 M faces, 10 holes", "Repair_Rangefill/708", "Repair_CgalFair/708");
  ratio("repair, 10 M faces, 10 holes", "Repair_Rangefill/2236", "Repair_CgalFair/2236");
  if (reporter.times.count("Read_AsciiPly")) {
    std::printf("%-44s %9.0f MB/s\n", "read_mesh, ASCII PLY",
                fs::file_size(files().ascii) / 1e6 / (reporter.times["Read_AsciiPly"] / 1e3));
  }
  benchmark::Shutdown();
  return 0;
}
