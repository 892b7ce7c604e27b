// rangefill repair IN -o OUT, or --batch DIR --out-dir DIR: close the holes of meshes.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>
#include <sstream>

#include "cli.h"
#include "hole_pictures.h"
#include "rangefill/core/errors.h"
#include "rangefill/io/depth_io.h"
#include "rangefill/point_cloud/point_cloud.h"
#include "rangefill/repair/pipeline.h"
#include "rangefill/reports/reports.h"

namespace rangefill::cli {

namespace {

namespace fs = std::filesystem;

// Defaults are RepairOptions' and FillerOptions' own: the library and the command repair alike.
struct RepairCommand {
  RepairOptions options;
  FillerOptions fillers;  // RepairOptions' chain and candidates are made with these
  std::string input, output, report, debug_dir, holes = "all", batch, out_dir, shard = "0/1";
  std::string trend = trend_name(fillers.plane.trend);
  std::string filler = kDefaultFiller;       // RepairOptions' chain: this filler and these
  std::string fallback = kDefaultFallbacks;  // fallbacks
  std::string mesher = "greedy";
  std::string select = kDefaultCandidates;
  bool in_place = false, json = false, ascii = false, fill_all = false;
  const CLI::App* app = nullptr;  // the sub-command, for which options were given
};

std::vector<int> parse_hole_ids(const std::string& text) {
  std::vector<int> ids;
  if (text == "all") return ids;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    try {
      size_t used = 0;
      ids.push_back(std::stoi(item, &used));
      if (used != item.size() || ids.back() < 0) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw UsageError("--holes: '" + item + "' is not a hole id (expected all or ID,ID,...)");
    }
  }
  return ids;
}

// 16-bit PNGs of one hole's range image: depth (0 = unknown), mask, restored depth; each written
// atomically.
void write_debug_images(const std::string& dir, const HoleImages& images) {
  const std::string stem = dir + "/hole-" + std::to_string(images.id);
  cv::Mat depth, restored;
  images.image.depth.convertTo(depth, CV_16U, 65535.0);
  depth.setTo(0, images.image.labels != kKnownPixel);
  images.restored.convertTo(restored, CV_16U, 65535.0);
  for (const auto& [suffix, image] : {std::pair{"-depth.png", depth},
                                      {"-mask.png", images.image.mask()},
                                      {"-restored.png", restored}}) {
    const std::string png = encode_png(image);
    const OutputGuard guard;
    write_file_atomically(png, stem + suffix);
  }
}

// --debug-dir after the repair: a picture of each filled hole (hole-<id>.png, before | after); the
// range images written for holes that the image pipeline then did not fill removed; what was
// written, or why nothing was, said on stderr.
void finish_debug_dir(const std::string& dir, const Mesh& input, const RepairResult& result,
                      const std::set<int>& imaged) {
  int pictures = 0, image_holes = 0;
  std::set<std::string> fillers;
  for (const HoleReport& hole : result.holes) {
    const bool by_images =
        hole.filled && imaged.count(hole.id) && hole.method.rfind("plane", 0) == 0;
    if (imaged.count(hole.id) && !by_images) {
      for (const char* suffix : {"-depth.png", "-mask.png", "-restored.png"}) {
        fs::remove(dir + "/hole-" + std::to_string(hole.id) + suffix);
      }
    }
    image_holes += by_images;
    if (!hole.filled) continue;
    fillers.insert(hole.filler);
    const cv::Mat picture = hole_picture(input, result.mesh, hole.id);
    if (picture.empty()) continue;
    const OutputGuard guard;
    write_file_atomically(encode_png(picture), dir + "/hole-" + std::to_string(hole.id) + ".png");
    ++pictures;
  }
  std::string said = "rangefill: note: --debug-dir " + dir + ": ";
  if (pictures == 0) {
    said += "no hole was repaired, nothing written";
  } else {
    said += "wrote a picture of each of the " + std::to_string(pictures) +
            " repaired holes (hole-ID.png: before | after, the fill in orange)";
    if (image_holes > 0) {
      said += " and the range images of the " + std::to_string(image_holes) +
              " the image pipeline filled (hole-ID-depth.png, -mask.png, -restored.png)";
    } else {
      std::string names;
      for (const std::string& name : fillers) names += (names.empty() ? "" : ", ") + name;
      said += "; no range images: no hole was filled by the image pipeline (filled by " + names +
              "; --filler plane puts it first)";
    }
  }
  std::cerr << said << "\n";
}

// What `work` returns; its InvalidInput says which file it is about.
template <typename Work>
auto naming_the_input(const std::string& input, Work work) {
  try {
    return work();
  } catch (const InvalidInput& error) {
    throw InvalidInput(input + ": " + error.what());
  }
}

// Throws UsageError when `path` (an output) names the same file as `other` (when that exists).
void refuse_same_file(const std::string& path, const std::string& other, const std::string& what) {
  std::error_code error;
  if (fs::exists(path) && fs::equivalent(path, other, error)) {
    throw UsageError(path + ": is the " + what + "; choose another file");
  }
}

nlohmann::json report_json(const RepairCommand& command, const RepairResult& result,
                           double seconds) {
  nlohmann::json report = reports::repair_report(result);
  report["input"] = command.input;
  report["output"] = command.output;
  report["inpainter"] = command.fillers.plane.inpainter;
  report["trend"] = command.trend;
  report["filler"] = command.filler;
  report["mesher"] = command.mesher;
  report["border_share"] = command.options.border_share;
  report["seconds"] = seconds;
  return report;
}

// "filled: fairing", or with a band test "filled: fairing:c1 (band test, RMS / d_m: fairing 0.31,
// fairing:c1 0.22, plane:telea refused)"; the failure when not filled.
std::string result_text(const HoleReport& hole) {
  if (!hole.filled) return hole.failure;
  if (hole.selected.empty()) return "filled: " + hole.method;
  std::string text = "filled: " + hole.selected + " (band test, RMS / d_m:";
  for (size_t i = 0; i < hole.selection.size(); ++i) {
    const CandidateScore& score = hole.selection[i];
    char value[32] = "refused";
    if (score.score) std::snprintf(value, sizeof value, "%.2f", *score.score);
    text += (i ? ", " : " ") + score.candidate + " " + value;
  }
  return text + ")";
}

void print_summary(const RepairResult& result) {
  std::printf("%5s %4s %9s %4s %11s %7s %8s %8s  %s\n", "hole", "pass", "boundary", "nu", "image",
              "masked", "new v", "seconds", "result");
  for (const HoleReport& hole : result.holes) {
    const std::string size =
        std::to_string(hole.image.width) + "x" + std::to_string(hole.image.height);
    std::printf("%5d %4d %9d %4d %11s %7d %8d %8.3f  %s\n", hole.id, hole.pass,
                hole.boundary_vertices, hole.rings, size.c_str(), hole.image.masked_pixels,
                hole.new_vertices, hole.seconds, result_text(hole).c_str());
  }
}

// "6 loops, 5 closed, 1 left open (1 border, 0 over a size limit, 0 failed)": the loops of the
// input (each tried in pass 0 or left open by the options), and those of the output by reason.
std::string loops_line(const RepairResult& result, bool listed) {
  int input_loops = 0;
  for (const HoleReport& hole : result.holes) input_loops += hole.pass == 0;
  std::set<int> open_input_loops;
  for (const OpenLoop& loop : result.open_loops) {
    input_loops += loop.reason != OpenReason::failed;
    open_input_loops.insert(loop.hole);
  }
  const int closed = static_cast<int>(
      std::count_if(result.holes.begin(), result.holes.end(), [&](const HoleReport& hole) {
        return hole.pass == 0 && open_input_loops.count(hole.id) == 0;
      }));
  std::string line = std::to_string(input_loops) + " loops, " + std::to_string(closed) +
                     " closed, " + std::to_string(result.open_loops.size()) + " left open (" +
                     std::to_string(result.open_count(OpenReason::border)) + " border, ";
  if (listed) {
    line += std::to_string(result.open_count(OpenReason::not_selected)) + " not selected, ";
  }
  return line + std::to_string(result.open_count(OpenReason::over_size_limit)) +
         " over a size limit, " + std::to_string(result.open_count(OpenReason::failed)) +
         " failed)";
}

// One note for the loops kept as borders, naming them.
void print_border_note(const RepairResult& result, double border_share) {
  std::string ids;
  for (const OpenLoop& loop : result.open_loops) {
    if (loop.reason != OpenReason::border) continue;
    ids += (ids.empty() ? "" : ", ") + std::to_string(loop.hole) + " (" +
           std::to_string(static_cast<int>(std::lround(100 * loop.area_share))) + " %)";
  }
  if (ids.empty()) return;
  std::cerr << "rangefill: note: left open as the border of an open surface (a fill would cover "
               "at least "
            << std::lround(100 * border_share) << " % of its component): loop " << ids
            << "; --fill-all fills them\n";
}

// The arguments checked and turned into options, before any work: outputs that are not the
// input (nor each other), known formats and names.
void check_arguments(RepairCommand& command) {
  if (!command.in_place && fs::exists(command.output) &&
      fs::equivalent(command.input, command.output)) {
    throw UsageError(command.output + ": is the input; pass --in-place to overwrite it");
  }
  if (!command.report.empty()) {
    refuse_same_file(command.report, command.input, "input");
    if (command.report == command.output) throw UsageError(command.report + ": is the output");
    refuse_same_file(command.report, command.output, "output");
  }
  format_from_extension(command.output);  // fail before the work, not after
  check_inpainter(command.fillers.plane.inpainter, "--inpainter");
  command.options.holes = parse_hole_ids(command.holes);
  command.fillers.plane.trend = trend_from_name(command.trend);
  if (command.fill_all) command.options.border_share = 0;
  command.options.chain = chain_from_arguments(command.filler, command.fallback, command.fillers);
  command.options.selection.candidates =
      candidates_from_arguments(*command.app, command.select, command.fillers);
}

// The input mesh; a point cloud meshed first (unless --mesher none, which refuses it).
Mesh load_input(const RepairCommand& command) {
  const Mesher mesher = mesher_from_name(command.mesher);
  Mesh mesh = load_mesh(command.input, ReadOptions{kFillShare});
  if (!mesh.triangles.empty()) return mesh;
  if (mesher == Mesher::none) {
    throw InvalidInput(command.input + ": a point cloud without faces (--mesher greedy meshes it)");
  }
  mesh = naming_the_input(command.input, [&] { return mesh_point_cloud(mesh); });
  std::cerr << "rangefill: note: " << command.input << ": meshed " << mesh.vertex_count()
            << " points into " << mesh.face_count() << " triangles (greedy projection)\n";
  return mesh;
}

// What repairing one file gave: the result, its report and the exit code it calls for.
struct FileRepair {
  RepairResult result;
  nlohmann::json report;
  int exit_code = kOk;
};

// Repairs command.input into command.output (and --report), with progress per hole on a terminal
// and the input's defects and border loops said on stderr.
FileRepair repair_file(RepairCommand& command) {
  check_arguments(command);
  Mesh mesh = load_input(command);

  const bool progress = stderr_is_terminal();
  int done = 0;
  command.options.on_hole = [&](const HoleReport& hole) {
    ++done;
    if (!progress) return;
    std::fprintf(stderr, "\r\033[K[%d] hole %d: %s", done, hole.id,
                 hole.filled
                     ? ("filled, " + std::to_string(hole.new_vertices) + " vertices").c_str()
                     : "left open");
    std::fflush(stderr);
  };
  Mesh input;            // kept for --debug-dir's pictures
  std::set<int> imaged;  // holes whose range images --debug-dir holds
  if (!command.debug_dir.empty()) {
    fs::create_directories(command.debug_dir);
    input = mesh;
    command.options.on_images = [&](const HoleImages& images) {
      write_debug_images(command.debug_dir, images);
      imaged.insert(images.id);
    };
  }

  const auto start = std::chrono::steady_clock::now();
  FileRepair repaired;
  repaired.result =
      naming_the_input(command.input, [&] { return repair(std::move(mesh), command.options); });
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  command.options.on_hole = nullptr;
  command.options.on_images = nullptr;
  if (progress && done > 0) std::fprintf(stderr, "\r\033[K");
  const RepairResult& result = repaired.result;

  WriteOptions write_options;
  if (command.ascii) write_options.encoding = Encoding::ascii;
  {
    const OutputGuard guard;
    write_mesh(result.mesh, command.output, write_options);
  }

  if (result.defects.any()) {
    std::cerr << "rangefill: warning: " << command.input << ": " << describe(result.defects)
              << "; holes that touch them are left open\n";
  }
  print_border_note(result, command.options.border_share);
  if (!command.debug_dir.empty()) finish_debug_dir(command.debug_dir, input, result, imaged);
  repaired.report = report_json(command, result, seconds);
  if (!command.report.empty()) {
    const OutputGuard guard;
    write_file_atomically(repaired.report.dump(2) + "\n", command.report);
  }
  const int failed = result.open_count(OpenReason::failed);
  if (failed > 0) {
    std::cerr << "rangefill: " << command.output
              << ": partial repair, loops left open that were to be filled: " << failed << "\n";
    repaired.exit_code = kPartial;
  }
  return repaired;
}

int run_single(RepairCommand& command) {
  const FileRepair repaired = repair_file(command);
  if (command.json) {
    print_json(repaired.report);
  } else {
    print_summary(repaired.result);
    std::printf("%s; %.3f s; wrote %s\n",
                loops_line(repaired.result, !command.options.holes.empty()).c_str(),
                repaired.report["seconds"].get<double>(), command.output.c_str());
  }
  return repaired.exit_code;
}

// --batch: every mesh of the directory in name order (this shard's share) into --out-dir, one
// after the other (the holes of each in parallel); a file that cannot be repaired is skipped and
// said, and the exit code is then 5, as it is when a repair is partial.
int run_batch(const RepairCommand& command) {
  if (!command.input.empty() || !command.output.empty() || !command.report.empty() ||
      !command.debug_dir.empty() || command.in_place) {
    throw UsageError(
        "--batch takes no input file, -o, --report, --debug-dir or --in-place (outputs go to "
        "--out-dir, under the inputs' names)");
  }
  if (command.out_dir.empty()) throw UsageError("--batch needs --out-dir");
  const std::pair<int, int> shard = parse_shard(command.shard);
  if (!fs::is_directory(command.batch)) throw IoError(command.batch + ": not a directory");
  fs::create_directories(command.out_dir);
  if (same_file(command.out_dir, command.batch)) {
    throw UsageError("--out-dir " + command.out_dir +
                     " is the input directory: the outputs would overwrite the inputs");
  }
  const std::vector<fs::path> all = mesh_files({command.batch});
  const std::vector<fs::path> files = shard_of(all, shard);
  const bool progress = stderr_is_terminal();
  nlohmann::json reports = nlohmann::json::array();
  int skipped = 0, partial = 0;
  const auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < files.size(); ++i) {
    if (progress) {
      std::fprintf(stderr, "\r\033[K[%zu/%zu] %s\n", i + 1, files.size(),
                   files[i].filename().c_str());
    }
    RepairCommand file_command = command;
    file_command.input = files[i].string();
    file_command.output = (fs::path(command.out_dir) / files[i].filename()).string();
    nlohmann::json entry = {{"input", file_command.input}};
    try {
      const FileRepair repaired = repair_file(file_command);
      partial += repaired.exit_code == kPartial;
      entry = repaired.report;
      entry["written"] = true;
      if (!command.json) {
        std::printf("%s: %s; %.3f s\n", file_command.input.c_str(),
                    loops_line(repaired.result, !command.options.holes.empty()).c_str(),
                    repaired.report["seconds"].get<double>());
      }
    } catch (const UsageError&) {
      throw;  // the same for every file
    } catch (const std::exception& error) {
      ++skipped;
      std::cerr << "rangefill: skipped " << error.what() << "\n";
      entry["written"] = false;
      entry["error"] = error.what();
    }
    reports.push_back(entry);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (command.json) {
    print_json(reports);
  } else {
    std::printf(
        "%zu files (shard %d/%d of %zu), %zu written to %s, %d skipped, %d partial; %.1f s\n",
        files.size(), shard.first, shard.second, all.size(), files.size() - skipped,
        command.out_dir.c_str(), skipped, partial, seconds);
  }
  return skipped + partial > 0 ? kPartial : kOk;
}

int run_repair(RepairCommand& command) {
  if (command.batch.empty() == command.input.empty()) {
    throw UsageError("give an input file (with -o OUT) or --batch DIR (with --out-dir DIR)");
  }
  if (command.batch.empty()) {
    if (command.output.empty()) throw UsageError("-o OUT is needed with an input file");
    return run_single(command);
  }
  return run_batch(command);
}

}  // namespace

void add_repair_command(CLI::App& app, Runner& runner) {
  auto command = std::make_shared<RepairCommand>();
  RepairOptions& options = command->options;
  PlaneFillerOptions& plane = command->fillers.plane;
  CLI::App* sub = app.add_subcommand("repair", "Fill the holes of a mesh (Pérez et al. pipeline)");
  command->app = sub;
  sub->add_option("input", command->input, "Mesh with holes (.ply, .obj, .off, .stl)");
  sub->add_option("-o,--output", command->output, "Repaired mesh (format from the extension)");
  sub->add_option("--batch", command->batch, "Repair every mesh of this directory");
  sub->add_option("--out-dir", command->out_dir, "Where --batch writes (same file names)");
  sub->add_option("--shard", command->shard,
                  "K/N: repair only files K, K+N, K+2N, ... of the directory in name order "
                  "(0-based), for job arrays")
      ->capture_default_str();
  sub->add_option("--filler", command->filler,
                  "What fills a hole first: fairing (Liepa's patch refined and faired, CGAL; "
                  "fairing:c0|c1|c2 of that continuity), plane (range images, Pérez et al.; "
                  "plane:BACKEND), front (advancing front, Tekumalla & Cohen), plane-in-part, "
                  "liepa or least-area")
      ->capture_default_str();
  sub->add_option(
         "--fallback", command->fallback,
         "What takes a hole the filler cannot fill, tried in the order listed: any filler, "
         "least-area standing for liepa,least-area (a patch of its loop without new vertices: "
         "Liepa's weight, else least area), or none")
      ->capture_default_str();
  sub->add_option("--select", command->select,
                  "Candidates scored on each hole by a band test (a band of known faces hidden "
                  "round the hole, the enlarged hole filled by each, the fill nearest the band "
                  "wins), tried before the filler: any filler (fairing[:c0|:c1|:c2], "
                  "plane[:BACKEND], front, ...); "
                  "or none (the default when --filler or --fallback is given without --select)")
      ->capture_default_str();
  sub->add_option("--select-band", options.selection.band_rings,
                  "Rings of known faces the band test hides round a hole")
      ->capture_default_str()
      ->check(CLI::Range(1, 20));
  sub->add_option("--mesher", command->mesher,
                  "For a point cloud (points, no faces): greedy (PCL's greedy projection, "
                  "Gopi & Krishnan) meshes it first; none refuses it")
      ->capture_default_str()
      ->check(CLI::IsMember({"greedy", "none"}));
  sub->add_option("--inpainter", plane.inpainter, inpainter_help())->capture_default_str();
  add_foe_inference_options(sub, plane.inpainting);
  sub->add_option("--alpha", plane.inpainting.mls.alpha,
                  "mls: alpha of the weights exp(-alpha d^2)/d^2 (eq. 6), d in pixels")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  sub->add_option("--radius", plane.inpainting.opencv.radius,
                  "Neighbourhood radius in pixels (telea, ns)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 100.0));
  sub->add_option(
         "--trend", command->trend,
         "Surface removed before inpainting and added back: none (the paper), plane, quadric, "
         "sphere, auto (the sphere where it fits the hole's surroundings better than the quadric)")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "plane", "quadric", "sphere", "auto"}));
  sub->add_option("--holes", command->holes,
                  "Holes to fill: all, or ids as listed by `rangefill holes`")
      ->capture_default_str();
  sub->add_option("--max-hole-size", options.max_hole_edges,
                  "Leave open holes with more boundary edges (0: no limit)");
  sub->add_option("--max-hole-area", options.max_hole_area,
                  "Leave open holes of larger area (0: no limit)");
  sub->add_option("--report", command->report, "Write a JSON report of every hole to this file");
  sub->add_option("--debug-dir", command->debug_dir,
                  "Write a picture of each repaired hole here (before | after), and the depth, "
                  "mask and restored images of the holes the image pipeline filled");
  sub->add_option("--threads", options.threads,
                  "Holes filled in parallel (the output does not depend on it)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  sub->add_option("--passes", options.passes, "Rounds of detect-fill-merge")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  sub->add_option("--beta", plane.image.beta, "Grid step q = beta * d_m (eq. 6)")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 4.0));
  sub->add_option("--gamma", options.zone.gamma_degrees,
                  "Normal-diffusion threshold in degrees (eq. 4)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 180.0));
  sub->add_option("--rings", options.zone.rings, "Rings of the zone of interest (0: eq. 2)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  CLI::Option* fill_all =
      sub->add_flag("--fill-all", command->fill_all,
                    "Also fill the loops taken for borders of an open surface (with --holes all)");
  sub->add_option("--border-share", options.border_share,
                  "A loop whose fill would cover at least this share of its component's surface "
                  "(its area_share, see `rangefill holes`) is the border of an open surface and "
                  "is left open, unless listed by --holes (0: none is)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0))
      ->excludes(fill_all);
  sub->add_flag("--ascii", command->ascii, "Write ASCII instead of binary (PLY, STL)");
  sub->add_flag("--in-place", command->in_place, "Allow OUT to be the input file");
  sub->add_flag("--json", command->json, "Print the report as JSON instead of a table");
  sub->callback([command, &runner] { runner = [command] { return run_repair(*command); }; });
}

}  // namespace rangefill::cli
