// rangefill depth IN -o OUT, or --batch DIR --out-dir DIR: fill the holes of depth images.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <mutex>

#include "cli.h"
#include "rangefill/core/errors.h"
#include "rangefill/core/parallel.h"
#include "rangefill/depth/fill_depth.h"
#include "rangefill/inpaint/inpainters.h"
#include "rangefill/io/depth_io.h"
#include "rangefill/reports/reports.h"

namespace rangefill::cli {

namespace {

namespace fs = std::filesystem;

struct DepthCommand {
  std::string input, output, mask, filled_mask, color, batch, out_dir, mask_dir, color_dir;
  std::string shard = "0/1";
  std::string trend = "none";
  int threads = hardware_threads();
  bool json = false;
  DepthFillOptions options;
};

// "12 holes, 11 filled (3052 pixels, 4 beside a depth edge); left: 1 hole, 25 pixels (at the
// border 1 / 25)": what is left only by the reasons that left something.
std::string stats_text(const DepthFillStats& stats) {
  std::string text = std::to_string(stats.holes) + " holes, " + std::to_string(stats.filled) +
                     " filled (" + std::to_string(stats.filled_pixels) + " pixels, " +
                     std::to_string(stats.at_edge) +
                     " beside a depth edge); left: " + std::to_string(stats.left_holes()) +
                     " holes, " + std::to_string(stats.left_pixels()) + " pixels";
  std::string reasons;
  for (const auto& [name, left] : {std::pair{"too large", stats.too_large},
                                   {"at the border", stats.at_border},
                                   {"without valid neighbours", stats.without_support}}) {
    if (left.holes == 0) continue;
    reasons += std::string(reasons.empty() ? "" : ", ") + name + " " + std::to_string(left.holes) +
               " / " + std::to_string(left.pixels);
  }
  return text + (reasons.empty() ? "" : " (" + reasons + ")");
}

struct FileFill {
  DepthFillStats stats;
  double fill_seconds = 0;  // fill_depth alone, no reading or writing
};

// The files of one fill: the depth image, and optionally its mask and its colour image.
struct FillInputs {
  fs::path depth, mask, color;
};

// Reads, fills and writes one image (no mask: fill the invalid pixels; a colour image guides the
// fill); with `filled_mask`, also the mask of the pixels filled (8-bit PNG, 255 = filled).
FileFill fill_file(const FillInputs& inputs, const fs::path& output, const fs::path& filled_mask,
                   DepthFillOptions options) {
  const cv::Mat depth = read_depth_image(inputs.depth);
  check_depth_format(output, depth.type());
  const cv::Mat mask_image = inputs.mask.empty() ? cv::Mat() : read_mask_image(inputs.mask);
  if (!inputs.color.empty()) options.color = read_color_image(inputs.color);
  cv::Mat filled;
  FileFill result;
  DepthFillStats& stats = result.stats;
  try {
    const auto start = std::chrono::steady_clock::now();
    stats = fill_depth(depth, mask_image, filled, options);
    result.fill_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } catch (const InvalidInput& error) {
    throw InvalidInput(
        inputs.depth.string() + (inputs.mask.empty() ? "" : " with mask " + inputs.mask.string()) +
        (inputs.color.empty() ? "" : " and colour " + inputs.color.string()) + ": " + error.what());
  }
  write_depth_image(filled, output);
  if (!filled_mask.empty()) write_mask_image(stats.filled_mask, filled_mask);
  return result;
}

int run_single(const DepthCommand& command) {
  if (command.output.empty()) throw UsageError("-o OUT is required with an input file");
  if (!is_depth_image_path(command.output)) {
    throw UsageError(command.output + ": unknown format (expected .png, .tif, .tiff or .exr)");
  }
  if (!command.filled_mask.empty() && !is_depth_image_path(command.filled_mask)) {
    throw UsageError(command.filled_mask + ": unknown format (expected .png, .tif or .tiff)");
  }
  for (const std::string& written : {command.output, command.filled_mask}) {
    if (!written.empty() && (same_file(written, command.input) ||
                             (!command.mask.empty() && same_file(written, command.mask)))) {
      throw UsageError(written + ": is an input; choose another output");
    }
  }
  if (!command.filled_mask.empty() &&
      (command.filled_mask == command.output || same_file(command.filled_mask, command.output))) {
    throw UsageError(command.filled_mask + ": is the output; choose another file");
  }
  const auto start = std::chrono::steady_clock::now();
  DepthFillOptions options = command.options;
  options.threads = command.threads;
  const FileFill fill = fill_file({command.input, command.mask, command.color}, command.output,
                                  command.filled_mask, options);
  const DepthFillStats& stats = fill.stats;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (command.json) {
    nlohmann::json report = reports::depth_fill_report(stats);
    report["input"] = command.input;
    report["output"] = command.output;
    report["seconds"] = seconds;
    report["fill_seconds"] = fill.fill_seconds;
    print_json(report);
  } else {
    std::printf("%s: %s; %.3f s; wrote %s\n", command.input.c_str(), stats_text(stats).c_str(),
                seconds, command.output.c_str());
  }
  return kOk;
}

struct FileOutcome {
  bool written = false;
  std::string error;
  DepthFillStats stats;
};

int run_batch(const DepthCommand& command) {
  if (!command.input.empty() || !command.output.empty() || !command.mask.empty() ||
      !command.filled_mask.empty() || !command.color.empty()) {
    throw UsageError(
        "--batch takes no input file, -o, --mask, --color or --filled-mask (outputs go to "
        "--out-dir, masks come from --mask-dir, colour images from --color-dir)");
  }
  for (const std::string& dir : {command.mask_dir, command.color_dir}) {
    if (!dir.empty() && !fs::is_directory(dir)) throw IoError(dir + ": not a directory");
  }
  if (command.out_dir.empty()) throw UsageError("--batch needs --out-dir");
  const auto [shard, shards] = parse_shard(command.shard);
  if (!fs::is_directory(command.batch)) throw IoError(command.batch + ": not a directory");
  fs::create_directories(command.out_dir);
  if (same_file(command.out_dir, command.batch)) {
    throw UsageError("--out-dir " + command.out_dir +
                     " is the input directory: the outputs would overwrite the inputs");
  }

  // Every depth image of the directory in name order; this shard takes every shards-th from shard.
  const std::vector<fs::path> all = files_from_arguments({command.batch}, is_depth_image_path);
  const std::vector<fs::path> files = shard_of(all, {shard, shards});

  std::vector<FileOutcome> outcomes(files.size());
  std::mutex progress_mutex;
  int done = 0;
  const bool progress = stderr_is_terminal();
  DepthFillOptions options = command.options;
  options.threads = 1;  // files in parallel, the holes of each in turn
  const auto start = std::chrono::steady_clock::now();
  parallel_for(static_cast<int>(files.size()), command.threads, [&](int i) {
    const fs::path output = fs::path(command.out_dir) / files[i].filename();
    FileOutcome& outcome = outcomes[i];
    try {
      if (same_file(output, files[i])) throw IoError(output.string() + ": is the input");
      // A frame's mask has its file name in --mask-dir; a frame without one is refused.
      fs::path mask;
      if (!command.mask_dir.empty()) {
        mask = fs::path(command.mask_dir) / files[i].filename();
        if (!fs::exists(mask)) throw IoError(files[i].string() + ": no mask " + mask.string());
        if (same_file(output, mask)) throw IoError(output.string() + ": is a mask");
      }
      // A frame's colour image has its file stem in --color-dir.
      fs::path color;
      if (!command.color_dir.empty()) {
        color = color_image_of(command.color_dir, files[i]);
        if (color.empty()) {
          throw IoError(files[i].string() + ": no colour image " +
                        (fs::path(command.color_dir) / files[i].stem()).string() +
                        ".{png,jpg,jpeg,tif,tiff}");
        }
      }
      outcome.stats = fill_file({files[i], mask, color}, output, {}, options).stats;
      outcome.written = true;
    } catch (const std::exception& error) {
      outcome.error = error.what();
    }
    if (!progress) return;
    const std::lock_guard<std::mutex> lock(progress_mutex);
    std::fprintf(stderr, "\r\033[K[%d/%zu] %s", ++done, files.size(), files[i].filename().c_str());
    std::fflush(stderr);
  });
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (progress) std::fprintf(stderr, "\r\033[K");

  int skipped = 0;
  nlohmann::json report = nlohmann::json::array();
  for (size_t i = 0; i < files.size(); ++i) {
    const FileOutcome& outcome = outcomes[i];
    skipped += !outcome.written;
    if (!outcome.written) std::cerr << "rangefill: skipped " << outcome.error << "\n";
    if (!command.json) continue;
    nlohmann::json entry =
        outcome.written ? reports::depth_fill_report(outcome.stats) : nlohmann::json::object();
    entry["input"] = files[i].string();
    entry["written"] = outcome.written;
    if (!outcome.written) entry["error"] = outcome.error;
    report.push_back(entry);
  }
  if (command.json) {
    print_json(report);
  } else {
    std::printf("%zu files (shard %d/%d of %zu), %zu written to %s, %d skipped; %.1f s\n",
                files.size(), shard, shards, all.size(), files.size() - skipped,
                command.out_dir.c_str(), skipped, seconds);
  }
  return skipped > 0 ? kPartial : kOk;
}

int run_depth(DepthCommand& command) {
  command.options.trend = trend_from_name(command.trend);
  if (command.batch.empty() == command.input.empty()) {
    throw UsageError("give an input file (with -o OUT) or --batch DIR (with --out-dir DIR)");
  }
  return command.batch.empty() ? run_single(command) : run_batch(command);
}

}  // namespace

void add_depth_command(CLI::App& app, Runner& runner) {
  auto command = std::make_shared<DepthCommand>();
  DepthFillOptions& options = command->options;
  CLI::App* sub = app.add_subcommand(
      "depth", "Fill the holes of depth images (16-bit PNG/TIFF in mm, float TIFF/EXR in m)");
  sub->add_option("input", command->input, "Depth image; 0 (or NaN) marks invalid pixels");
  sub->add_option("-o,--output", command->output, "Filled depth image (format from the extension)");
  sub->add_option("--mask", command->mask,
                  "Pixels to fill: non-zero in this one-channel image (default: the invalid ones)");
  sub->add_option("--filled-mask", command->filled_mask,
                  "Write the mask of the pixels filled here (8-bit PNG, 255 = filled)");
  sub->add_option("--mask-dir", command->mask_dir,
                  "With --batch: each frame's mask, the file of the same name in this directory");
  sub->add_option("--color", command->color,
                  "Colour image registered to the depth (8-bit RGB or grey, PNG/JPEG/TIFF, same "
                  "size): its edges part the surfaces of a hole");
  sub->add_option("--color-dir", command->color_dir,
                  "With --batch: each frame's colour image, the file of the same stem in this "
                  "directory");
  sub->add_option("--batch", command->batch, "Fill every depth image of this directory");
  sub->add_option("--out-dir", command->out_dir, "Where --batch writes (same file names)");
  sub->add_option("--threads", command->threads,
                  "Files filled in parallel with --batch, else holes of the one file (the "
                  "outputs do not depend on it)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  sub->add_option(
         "--shard", command->shard,
         "K/N: fill only files K, K+N, K+2N, ... of the directory in name order (0-based), "
         "for job arrays")
      ->capture_default_str();
  CLI::Option* inpainter =
      sub->add_option(
             "--inpainter", options.inpainter,
             "Back-end for holes of up to --backend-max-pixels (larger ones along rows, columns "
             "and diagonals), or " +
                 std::string(kAlongLines) + " for every hole: " + join(inpainter_names()))
          ->capture_default_str()
          ->check(CLI::IsMember(depth_filler_names()));
  add_foe_inference_options(sub, options.inpainting);
  sub->add_flag("--fast", options.fast,
                "Fill along rows, columns and diagonals without looking for occluding edges "
                "hole by hole: a few ms a VGA frame, less accurate at depth edges")
      ->excludes(inpainter);
  sub->add_option("--backend-max-pixels", options.backend_max_pixels,
                  "Largest hole (pixels) the back-end fills; larger ones are filled along lines "
                  "(0: every hole by the back-end)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--max-hole", options.max_hole_pixels,
                  "Leave holes of more pixels as they are (0, the default: no limit)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sub->add_flag("--keep-border", options.keep_border,
                "Leave holes that touch the image border as they are (filled by default)");
  sub->add_option("--reach", options.reach,
                  "Pixels farther than this from every pixel a hole is filled from take the "
                  "nearest one's depth; the back-end fills the band within (0: no limit)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--discontinuity", options.discontinuity,
                  "Relative depth jump that separates two surfaces around a hole")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  sub->add_option("--trend", command->trend,
                  "Surface fitted around each hole and removed before the back-end")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "plane", "quadric"}));
  sub->add_option("--radius", options.inpainting.opencv.radius,
                  "Neighbourhood radius in pixels (telea, ns)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 100.0));
  sub->add_flag("--json", command->json, "Print what was done as JSON");
  sub->callback([command, &runner] { runner = [command] { return run_depth(*command); }; });
}

}  // namespace rangefill::cli
