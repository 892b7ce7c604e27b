// rangefill depth-bench: sensor-like holes punched into depth frames (rendered from meshes, or
// recorded by sensors), filled by fill_depth along lines and with each back-end, by plain
// cv::inpaint and, on sensor frames with a colour image (color/<stem>.* beside them), by fill_depth
// guided by it and by OpenCV contrib's fast bilateral solver; measured.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>

#include "cli.h"
#include "rangefill/core/render.h"
#include "rangefill/depth/fill_depth.h"
#include "rangefill/eval/depth_baselines.h"
#include "rangefill/eval/punch.h"
#include "rangefill/eval/sensor_holes.h"
#include "rangefill/io/depth_io.h"
#include "research.h"

namespace rangefill::cli {

namespace {

namespace fs = std::filesystem;

struct DepthBenchCommand {
  std::vector<std::string> meshes, frames;
  std::string inpainters, csv, save, trend = "none";
  int views = 2, patterns = 3;
  SensorHoleOptions holes;
  DepthFillOptions fill;
};

// The scene a mesh is rendered in: the mesh scaled to a 1 m bounding-box diagonal and centred on
// the origin, standing on a floor (y = its lowest point), with a wall 0.9 m behind it as seen from
// the camera, which is 1.6 m away at `azimuth` and 20° above the horizon, looking at the origin.
struct Scene {
  Mesh mesh;
  Eigen::Isometry3d pose;
};

Scene make_scene(const Mesh& object, double azimuth) {
  const auto [lowest, highest] = bounding_box(object);
  const Vec3 centre = (lowest + highest) / 2;
  const double scale = 1 / (highest - lowest).norm();
  Scene scene;
  for (const Vec3& p : object.positions) scene.mesh.positions.push_back((p - centre) * scale);
  scene.mesh.triangles = object.triangles;
  const double elevation = 20 * M_PI / 180, distance = 1.6, far = 20;
  const Vec3 towards_camera(std::sin(azimuth), 0, std::cos(azimuth));
  const Vec3 side(towards_camera.z(), 0, -towards_camera.x());
  const double floor = (lowest.y() - centre.y()) * scale;
  const Vec3 wall = -0.9 * towards_camera;
  const auto add_quad = [&](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const int first = scene.mesh.vertex_count();
    for (const Vec3& p : {a, b, c, d}) scene.mesh.positions.push_back(p);
    scene.mesh.triangles.push_back({first, first + 1, first + 2});
    scene.mesh.triangles.push_back({first, first + 2, first + 3});
  };
  const Vec3 up(0, 1, 0);
  add_quad(wall - far * side + floor * up, wall + far * side + floor * up,
           wall + far * side + far * up, wall - far * side + far * up);
  add_quad(wall - far * side + floor * up, wall + far * side + floor * up,
           wall + far * side + floor * up + far * towards_camera,
           wall - far * side + floor * up + far * towards_camera);
  scene.mesh = make_mesh(scene.mesh.positions, scene.mesh.triangles);
  const Vec3 eye = distance * (std::cos(elevation) * towards_camera + std::sin(elevation) * up);
  scene.pose = look_at(eye, Vec3::Zero(), up);
  return scene;
}

struct Frame {
  std::string dataset, name;
  cv::Mat truth;  // CV_16UC1, millimetres
  cv::Mat color;  // CV_8UC3, or empty: a sensor frame's colour image (its folder's color/)
};

// Errors and times of one method over a dataset.
struct Tally {
  double squared = 0, absolute = 0, pixels = 0;
  long long unfilled = 0;
  std::vector<double> milliseconds;
};

template <typename Run>
double milliseconds_of(Run run) {
  const auto start = std::chrono::steady_clock::now();
  run();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// The frames: each mesh rendered from `views` azimuths, then the depth images given.
std::vector<Frame> bench_frames(const DepthBenchCommand& command) {
  std::vector<Frame> frames;
  const CameraIntrinsics camera;
  for (const fs::path& file : mesh_files(command.meshes)) {
    const Mesh mesh = load_mesh(file.string());
    for (int view = 0; view < command.views; ++view) {
      const Scene scene = make_scene(mesh, 2 * M_PI * (view + 0.25) / command.views);
      cv::Mat millimetres;
      render_depth(scene.mesh, camera, scene.pose, {640, 480}).convertTo(millimetres, CV_16U, 1000);
      frames.push_back(
          {"rendered", file.stem().string() + "-" + std::to_string(view), millimetres, {}});
    }
  }
  for (const fs::path& file : files_from_arguments(command.frames, is_depth_image_path)) {
    cv::Mat depth = read_depth_image(file);
    if (depth.type() == CV_32FC1) depth.convertTo(depth, CV_16U, 1000);  // NaN → 0
    const fs::path color = color_image_of(file.parent_path() / "color", file);
    cv::Mat color_image;
    if (!color.empty()) {
      color_image = read_color_image(color);
      if (color_image.channels() == 1) cv::cvtColor(color_image, color_image, cv::COLOR_GRAY2BGR);
    }
    frames.push_back({"sensor", file.stem().string(), depth, color_image});
  }
  return frames;
}

// cv::inpaint on the 16-bit frame, the radius as ours, masking the punched pixels or all invalid.
struct CvInpaint {
  std::string name;
  int flags;
  bool mask_all_invalid;
};
const std::vector<CvInpaint> kCvInpaints = {
    {"cv::inpaint ns, punched mask", cv::INPAINT_NS, false},
    {"cv::inpaint ns, all invalid masked", cv::INPAINT_NS, true},
    {"cv::inpaint telea, punched mask", cv::INPAINT_TELEA, false},
    {"cv::inpaint telea, all invalid masked", cv::INPAINT_TELEA, true},
};

// Squared and absolute errors (mm) of `output` over the punched pixels, and those left at 0
// (counted as fills at 0 mm: cv::inpaint's fills drag towards it).
struct FrameErrors {
  double squared = 0, absolute = 0;
  long long unfilled = 0;
};
FrameErrors errors_over(const cv::Mat& output, const cv::Mat& truth, const cv::Mat& punched) {
  FrameErrors errors;
  for (int row = 0; row < truth.rows; ++row) {
    for (int col = 0; col < truth.cols; ++col) {
      if (!punched.at<std::uint8_t>(row, col)) continue;
      const int value = output.at<std::uint16_t>(row, col);
      errors.unfilled += value == 0;
      const double error = value - truth.at<std::uint16_t>(row, col);
      errors.squared += error * error;
      errors.absolute += std::abs(error);
    }
  }
  return errors;
}

// The table of one dataset, the best and fastest back-ends named.
void print_dataset(const std::string& dataset, const std::map<std::string, Tally>& by_method,
                   const std::vector<std::string>& methods, size_t backend_count, int frames,
                   long long punched, double fraction) {
  std::printf("%s frames: %d (holes: %.1f%% of the valid pixels, %lld punched pixels)\n",
              dataset.c_str(), frames, 100 * fraction, punched);
  std::printf("  %-40s %9s %9s %10s %9s\n", "method", "RMSE mm", "MAE mm", "ms/frame", "left at 0");
  std::string best_backend, fastest_backend, best_baseline;
  double best_rmse = INFINITY, fastest_ms = INFINITY, baseline_rmse = INFINITY;
  for (size_t m = 0; m < methods.size(); ++m) {
    const auto found = by_method.find(methods[m]);
    if (found == by_method.end()) continue;  // a colour method, and no frame had colour
    const Tally& tally = found->second;
    const double rmse = std::sqrt(tally.squared / tally.pixels);
    const double ms = median(tally.milliseconds);
    std::printf("  %-40s %9.1f %9.1f %10.1f %9lld\n", methods[m].c_str(), rmse,
                tally.absolute / tally.pixels, ms, tally.unfilled);
    if (m < backend_count) {
      if (rmse < best_rmse) best_rmse = rmse, best_backend = methods[m];
      if (ms < fastest_ms) fastest_ms = ms, fastest_backend = methods[m];
    } else if (methods[m].rfind("cv::inpaint", 0) == 0 && rmse < baseline_rmse) {
      baseline_rmse = rmse, best_baseline = methods[m];
    }
  }
  std::printf(
      "  best: %s, RMSE %.0f%% below the best cv::inpaint (%s); fastest: %s, %.1f ms/frame\n",
      best_backend.c_str(), 100 * (1 - best_rmse / baseline_rmse), best_baseline.c_str(),
      fastest_backend.c_str(), fastest_ms);
}

// The back-ends of --inpainters (all when empty); UsageError on an unknown one.
std::vector<std::string> bench_backends(const DepthBenchCommand& command) {
  std::vector<std::string> backends = split_list(command.inpainters);
  if (backends.empty()) backends = depth_filler_names();
  const std::vector<std::string> known = depth_filler_names();
  for (const std::string& name : backends) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      throw UsageError("--inpainters: unknown back-end '" + name + "' (known: " + join(known) +
                       ")");
    }
  }
  return backends;
}

int run_depth_bench(const DepthBenchCommand& command) {
  const std::vector<std::string> backends = bench_backends(command);
  DepthFillOptions fill = command.fill;
  fill.trend = trend_from_name(command.trend);
  if (command.meshes.empty() && command.frames.empty()) {
    throw UsageError("give --meshes, --frames or both");
  }
  const std::vector<Frame> frames = bench_frames(command);
  // Methods: fill_depth with each back-end, then cv::inpaint.
  std::vector<std::string> methods;
  for (const std::string& name : backends) methods.push_back("fill_depth " + name);
  for (const CvInpaint& baseline : kCvInpaints) methods.push_back(baseline.name);
  // On the frames with a colour image: the default with it, and OpenCV contrib's solver.
  const size_t first_colour_method = methods.size();
  methods.push_back("fill_depth, colour-guided");
  methods.push_back("fast bilateral solver, colour-guided");

  std::map<std::string, std::map<std::string, Tally>> tallies;  // dataset → method → tally
  std::map<std::string, int> frame_counts;
  std::map<std::string, long long> punched_pixels;
  std::ofstream csv;
  if (!command.csv.empty()) {
    csv.open(command.csv);
    csv << "dataset,frame,pattern,method,punched,unfilled,rmse_mm,mae_mm,ms\n";
  }
  if (!command.save.empty()) fs::create_directories(command.save);
  const bool progress = stderr_is_terminal();
  for (const Frame& frame : frames) {
    for (int pattern = 0; pattern < command.patterns; ++pattern) {
      if (progress) {
        std::fprintf(stderr, "\r\033[K%s %s #%d", frame.dataset.c_str(), frame.name.c_str(),
                     pattern);
      }
      SensorHoleOptions holes = command.holes;
      holes.seed = seed_for_mesh(command.holes.seed, frame.name) + pattern;
      const cv::Mat punched = punch_depth_holes(frame.truth, holes);
      cv::Mat input = frame.truth.clone();
      input.setTo(0, punched);
      const cv::Mat all_invalid = input == 0;
      const double pixels = std::max(1, cv::countNonZero(punched));
      ++frame_counts[frame.dataset];
      punched_pixels[frame.dataset] += cv::countNonZero(punched);
      const std::string stem =
          command.save + "/" + frame.dataset + "-" + frame.name + "-" + std::to_string(pattern);
      if (!command.save.empty()) {
        write_depth_image(frame.truth, stem + "-truth.png");
        write_depth_image(input, stem + "-input.png");
      }
      for (size_t m = 0; m < methods.size(); ++m) {
        if (m >= first_colour_method && frame.color.empty()) continue;
        cv::Mat output;
        DepthFillOptions options = fill;
        if (m < backends.size()) options.inpainter = backends[m];
        const double ms = milliseconds_of([&] {
          if (m < backends.size()) {
            fill_depth(input, punched, output, options);
          } else if (m == first_colour_method) {
            options.color = frame.color;
            fill_depth(input, punched, output, options);
          } else if (m > first_colour_method) {
            output = fill_depth_fast_bilateral_solver(input, frame.color, punched);
          } else {
            const CvInpaint& baseline = kCvInpaints[m - backends.size()];
            cv::inpaint(input, baseline.mask_all_invalid ? all_invalid : punched, output,
                        command.fill.inpainting.opencv.radius, baseline.flags);
          }
        });
        const FrameErrors errors = errors_over(output, frame.truth, punched);
        Tally& tally = tallies[frame.dataset][methods[m]];
        tally.milliseconds.push_back(ms);
        tally.squared += errors.squared;
        tally.absolute += errors.absolute;
        tally.pixels += pixels;
        tally.unfilled += errors.unfilled;
        if (csv.is_open()) {
          csv << frame.dataset << ',' << frame.name << ',' << pattern << ",\"" << methods[m]
              << "\"," << pixels << ',' << errors.unfilled << ','
              << std::sqrt(errors.squared / pixels) << ',' << errors.absolute / pixels << ',' << ms
              << '\n';
        }
        if (!command.save.empty() && m < backends.size()) {
          write_depth_image(output, stem + "-" + backends[m] + ".png");
        }
      }
    }
  }
  if (progress) std::fprintf(stderr, "\r\033[K");
  for (const auto& [dataset, by_method] : tallies) {
    print_dataset(dataset, by_method, methods, backends.size(), frame_counts[dataset],
                  punched_pixels[dataset], command.holes.fraction);
  }
  return kOk;
}

}  // namespace

void add_depth_bench_command(CLI::App& app, Runner& runner) {
  auto command = std::make_shared<DepthBenchCommand>();
  CLI::App* sub = app.add_subcommand(
      "depth-bench",
      "Punch sensor-like holes into depth frames, fill them with each back-end and with "
      "cv::inpaint, and measure");
  sub->add_option("--meshes", command->meshes,
                  "Meshes (or directories of them) rendered as 640x480 depth frames");
  sub->add_option("--frames", command->frames,
                  "Depth frames (16-bit PNG/TIFF in mm, float TIFF/EXR in m), or directories of "
                  "them");
  sub->add_option("--views", command->views, "Frames rendered per mesh")
      ->capture_default_str()
      ->check(CLI::Range(1, 360));
  sub->add_option("--patterns", command->patterns, "Hole patterns punched per frame")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  sub->add_option("--fraction", command->holes.fraction, "Share of the valid pixels punched")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 0.5));
  sub->add_option("--seed", command->holes.seed, "Seed of the holes")->capture_default_str();
  sub->add_option("--inpainters", command->inpainters, "Comma-separated back-ends (default: all)");
  add_foe_inference_options(sub, command->fill.inpainting);
  sub->add_option("--threads", command->fill.threads,
                  "Holes of a frame filled at once by fill_depth (cv::inpaint runs as it does)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  sub->add_option("--discontinuity", command->fill.discontinuity,
                  "Relative depth jump between two surfaces (fill_depth)")
      ->capture_default_str();
  sub->add_option("--trend", command->trend, "Trend of fill_depth: none, plane, quadric")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "plane", "quadric"}));
  sub->add_option("--csv", command->csv, "Write one row per frame, pattern and method here");
  sub->add_option("--save", command->save, "Write every frame, its holes and each fill here");
  sub->callback([command, &runner] { runner = [command] { return run_depth_bench(*command); }; });
}

}  // namespace rangefill::cli
