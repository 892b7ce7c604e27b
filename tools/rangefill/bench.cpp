// rangefill bench: punch holes into closed meshes, fill each with every back-end and baseline (one
// child process per hole and method), and measure as Pérez et al., Section X.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <sstream>

#include "bench_report.h"
#include "cli.h"
#include "isolation.h"
#include "kit_punch.h"
#include "rangefill/core/errors.h"
#include "rangefill/eval/evaluation.h"
#include "rangefill/eval/metrics.h"
#include "rangefill/eval/punch.h"
#include "rangefill/inpaint/inpainters.h"
#include "rangefill/io/depth_io.h"
#include "research.h"

namespace rangefill::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct BenchCommand {
  std::vector<std::string> meshes;
  std::vector<std::string> punched;  // the mesh kit's punch directories, instead of meshes
  std::string inpainters, baselines, trends = "auto", csv, save, out, filler = kDefaultFiller;
  std::string fallback = kDefaultFallbacks, shapes = "disk,elongated", shard;
  std::string select = "fairing,fairing:c1,plane";  // "plane": each method's own back-end
  const CLI::App* app = nullptr;                    // the sub-command, for which options were given
  std::vector<std::string> merge;                   // shard directories to make the report of
  PunchOptions punch = [] {
    PunchOptions options;
    options.max_radius = 20;
    options.spread = true;
    return options;
  }();
  InpainterOptions inpainting;
  int threads = 1, area_classes = 10;
  double timeout = 300, tie = 0.01;
  bool json = false;
};

// A mesh with its holes punched.
struct Punched {
  std::string name;
  Mesh original;
  PunchResult punched;
  std::vector<int> loops;  // punched_loops
  double mean_edge = 0;
};

// An 8-bit PNG, base64: `image` (values in [0, 1], saturated) times 255.
std::string png_base64(const cv::Mat& image) {
  cv::Mat bytes;
  image.convertTo(bytes, CV_8U, 255.0);
  return base64(encode_png(bytes));
}

json score_json(const HoleScore& s) {
  json steps = json::array();
  for (const StepSeconds& step : s.steps) steps.push_back({step.step, step.seconds});
  return {{"hole", s.hole},
          {"area", s.area},
          {"filled", s.filled},
          {"failure", s.failure},
          {"distance",
           {s.distance.hausdorff, s.distance.from_first, s.distance.from_second, s.distance.mean}},
          {"edge_ratio", s.edge_ratio},
          {"smallest_angle", s.smallest_angle},
          {"new_vertices", s.new_vertices},
          {"new_faces", s.new_faces},
          {"seconds", s.seconds},
          {"method", s.method},
          {"selected", s.selected},
          {"zone_faces", s.zone_faces},
          {"steps", steps}};
}

HoleScore score_from_json(const json& j) {
  HoleScore s;
  s.hole = j.at("hole");
  s.area = j.at("area");
  s.filled = j.at("filled");
  s.failure = j.at("failure");
  const json& d = j.at("distance");
  s.distance = {d[0], d[1], d[2], d[3]};
  s.edge_ratio = j.at("edge_ratio");
  s.smallest_angle = j.at("smallest_angle");
  s.new_vertices = j.at("new_vertices");
  s.new_faces = j.at("new_faces");
  s.seconds = j.at("seconds");
  s.method = j.at("method");
  s.selected = j.at("selected");
  s.zone_faces = j.at("zone_faces");
  for (const json& step : j.at("steps")) s.steps.push_back({step[0], step[1]});
  return s;
}

// A mesh's positions and triangles, [[x, y, z]...], [[a, b, c]...].
json mesh_json(const Mesh& mesh) {
  json positions = json::array(), triangles = json::array();
  for (const Vec3& p : mesh.positions) positions.push_back({p.x(), p.y(), p.z()});
  for (const Triangle& t : mesh.triangles) triangles.push_back(t);
  return {positions, triangles};
}

Mesh mesh_from_json(const json& j) {
  Mesh mesh;
  for (const auto& p : j.at(0)) mesh.positions.emplace_back(p[0], p[1], p[2]);
  for (const auto& t : j.at(1)) mesh.triangles.push_back(t.get<Triangle>());
  return mesh;
}

// What a child sends back for one method on one hole.
std::string run_json(const HoleRun& run, bool images, bool patch) {
  json j = {{"score", score_json(run.score)},
            {"self_intersections", run.self_intersections},
            {"manifold", run.manifold},
            {"wall_seconds", run.wall_seconds}};
  if (images && !run.depth.empty()) {
    cv::Mat known = run.depth.clone();
    known.setTo(0, run.labels != kKnownPixel);
    j["images"] = {png_base64(known), png_base64(run.labels == kHolePixel),
                   png_base64(run.restored)};
  }
  if (patch) j["patch"] = mesh_json(run.patch);
  return j.dump();
}

// What a child reported for one job, as kept in a shard file: its run (run_json), or why it did
// not report and how long it took.
json job_entry(const ChildResult& child) {
  if (child.completed) return json::parse(child.output);
  return {{"failure", child.failure}, {"wall_seconds", child.seconds}};
}

// The run of a job entry (job_entry), with its patch if it sent one.
BenchRun run_from_entry(const json& j, const BenchHole& hole) {
  BenchRun run;
  run.wall_seconds = j.at("wall_seconds");
  if (!j.contains("score")) {
    run.score.hole = hole.index;
    run.score.area = hole.hole.area;
    run.score.failure = j.at("failure");
    return run;
  }
  run.score = score_from_json(j.at("score"));
  run.self_intersections = j.at("self_intersections");
  run.manifold = j.at("manifold");
  if (j.contains("images")) {
    run.depth_png = j["images"][0];
    run.mask_png = j["images"][1];
    run.restored_png = j["images"][2];
  }
  if (j.contains("patch")) run.patch = mesh_from_json(j["patch"]);
  return run;
}

// The parts as one mesh, each part's elements marked with its index (as a hole).
Mesh marked_union(const std::vector<Mesh>& parts) {
  Mesh all;
  for (size_t i = 0; i < parts.size(); ++i) {
    const int offset = all.vertex_count();
    for (const Vec3& p : parts[i].positions) add_vertex(all, p, static_cast<int>(i));
    for (Triangle t : parts[i].triangles) {
      for (int& v : t) v += offset;
      add_face(all, t, static_cast<int>(i));
    }
  }
  return all;
}

std::string csv_text(const std::string& text) {
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string csv_table(const BenchResults& results) {
  std::ostringstream csv;
  csv.precision(17);
  csv << "mesh,method,hole,area,filled,hausdorff,from_patch,from_truth,mean_distance,d_m,"
         "edge_ratio,new_vertices,new_faces,seconds,filler,zone_faces,zone_s,planes_s,image_s,"
         "inpainting_s,stitching_s,checking_s,front_s,failure,shape,radius_dm,length_dm,area_dm2,"
         "bending,curvature,sharp_feature,hausdorff_dm,from_patch_dm,from_truth_dm,"
         "mean_distance_dm,self_intersections,manifold,wall_s,selected,smallest_angle_deg\n";
  for (size_t h = 0; h < results.holes.size(); ++h) {
    const BenchHole& hole = results.holes[h];
    const double d_m = hole.mean_edge;
    for (size_t m = 0; m < results.methods.size(); ++m) {
      const BenchRun& run = results.runs[h][m];
      const HoleScore& s = run.score;
      const SurfaceDistance& d = s.distance;
      csv << hole.mesh << ',' << results.methods[m] << ',' << hole.index << ',' << hole.hole.area
          << ',' << s.filled << ',' << d.hausdorff << ',' << d.from_first << ',' << d.from_second
          << ',' << d.mean << ',' << d_m << ',' << s.edge_ratio << ',' << s.new_vertices << ','
          << s.new_faces << ',' << s.seconds << ',' << csv_text(s.method) << ',' << s.zone_faces
          << ',' << seconds_of(s.steps, "zone") << ',' << seconds_of(s.steps, "planes") << ','
          << seconds_of(s.steps, "image") << ',' << seconds_of(s.steps, "inpainting") << ','
          << seconds_of(s.steps, "stitching") << ',' << seconds_of(s.steps, "checking") << ','
          << seconds_of(s.steps, "front") << ',' << csv_text(s.failure) << ','
          << shape_name(hole.hole.shape) << ',' << hole.hole.radius / d_m << ','
          << hole.hole.length / d_m << ',' << hole.hole.area / (d_m * d_m) << ','
          << hole.hole.bending << ',' << curvature_name(hole.hole.curvature) << ','
          << hole.hole.sharp_feature << ',' << d.hausdorff / d_m << ',' << d.from_first / d_m << ','
          << d.from_second / d_m << ',' << d.mean / d_m << ',' << run.self_intersections << ','
          << run.manifold << ',' << run.wall_seconds << ',' << csv_text(s.selected) << ','
          << s.smallest_angle << '\n';
    }
  }
  return csv.str();
}

// Writes `bytes` to `path` atomically, unless `path` is one of the input meshes.
void write_output(const std::string& bytes, const fs::path& path,
                  const std::vector<fs::path>& inputs) {
  std::error_code error;
  for (const fs::path& input : inputs) {
    if (fs::exists(path) && fs::equivalent(path, input, error)) {
      throw UsageError(path.string() + ": is an input mesh; choose another place");
    }
  }
  const OutputGuard guard;
  write_file_atomically(bytes, path);
}

void print_summary(const BenchResults& results, const BenchSummary& summary,
                   const BenchCommand& command) {
  if (command.punched.empty()) {
    std::printf("%d meshes, %zu holes (%d asked per mesh, seed %llu)\n", summary.meshes,
                results.holes.size(), command.punch.holes,
                static_cast<unsigned long long>(command.punch.seed));
  } else {
    std::printf("%d meshes, %zu holes (punched by the mesh kit)\n", summary.meshes,
                results.holes.size());
  }
  std::printf("%-18s %7s %7s %8s %17s %8s %8s %13s %9s %6s %6s %8s\n", "method", "filled", "closed",
              "H med/dm", "low/medium/high", "H max/dm", "mean/dm", "edge r", "min angle", "PCC",
              "self-x", "s/hole");
  for (size_t m = 0; m < results.methods.size(); ++m) {
    const MethodSummary& s = summary.methods[m];
    char edge[32];
    std::snprintf(edge, sizeof edge, "%.2f ± %.2f", s.edge_ratio.mean, s.edge_ratio.sd);
    char pcc[16] = "—";  // fewer than two holes, or H or the area constant
    if (!std::isnan(s.pearson)) std::snprintf(pcc, sizeof pcc, "%.2f", s.pearson);
    const auto& by_class = s.hausdorff_median_by_curvature;
    std::printf(
        "%-18s %3d/%-3zu %3d/%-3d %8.3f %5.3f/%5.3f/%5.3f %8.3f %8.3f %13s %9.1f %6s %6d "
        "%8.4f\n",
        results.methods[m].c_str(), s.filled, results.holes.size(), s.closed_meshes, summary.meshes,
        s.hausdorff_median, by_class[0], by_class[1], by_class[2], s.hausdorff_max,
        s.mean_distance_mean, edge, s.smallest_angle, pcc, s.self_intersections, s.seconds_median);
  }
  bool header = false;
  for (size_t m = 0; m < results.methods.size(); ++m) {
    const MethodSummary& s = summary.methods[m];
    if (s.chosen_holes.empty()) continue;
    if (!header) {
      std::printf("\nwhere the band test chose the image pipeline, H median / d_m of:\n%-18s %5s",
                  "back-end", "holes");
      for (const std::string& method : results.methods) std::printf(" %10.10s", method.c_str());
      std::printf("\n");
      header = true;
    }
    std::printf("%-18s %5zu", results.methods[m].c_str(), s.chosen_holes.size());
    for (double value : s.hausdorff_median_where_chosen) std::printf(" %10.3f", value);
    std::printf("\n");
  }
  std::printf(
      "\nplaces by H (Table 3) on %zu holes (every back-end filled %d of them alike), %%:\n%-18s",
      results.holes.size(), summary.alike_holes, "method");
  for (size_t p = 1; p <= results.methods.size(); ++p) std::printf(" %6zu", p);
  std::printf("\n");
  for (size_t m = 0; m < results.methods.size(); ++m) {
    std::printf("%-18s", results.methods[m].c_str());
    for (double share : summary.overall.shares[m]) std::printf(" %6.1f", 100 * share);
    std::printf("\n");
  }
}

// The back-ends to run: --inpainters, or all of them when neither they nor baselines are named.
std::vector<std::string> bench_inpainters(const BenchCommand& command) {
  std::vector<std::string> inpainters = split_list(command.inpainters);
  if (inpainters.empty() && command.baselines.empty()) inpainters = inpainter_names();
  return inpainters;
}

// How many of bench_methods are back-ends (they come first).
int backend_count(const BenchCommand& command) {
  return static_cast<int>(bench_inpainters(command).size() * split_list(command.trends).size());
}

// The methods to compare: every back-end with every trend, then the baselines.
std::vector<BenchmarkMethod> bench_methods(const BenchCommand& command) {
  const std::vector<std::string> inpainters = bench_inpainters(command);
  for (const std::string& name : inpainters) check_inpainter(name, "--inpainters");
  std::vector<TrendKind> trends;
  for (const std::string& name : split_list(command.trends))
    trends.push_back(trend_from_name(name));
  std::vector<BenchmarkMethod> methods;
  for (const std::string& inpainter : inpainters) {
    for (TrendKind trend : trends) {
      FillerOptions fillers;
      fillers.plane.inpainter = inpainter;
      fillers.plane.inpainting = command.inpainting;
      fillers.plane.trend = trend;
      RepairOptions options;
      options.chain = chain_from_arguments(command.filler, command.fallback, fillers);
      options.selection.candidates =
          candidates_from_arguments(*command.app, command.select, fillers);
      methods.push_back(
          pipeline_method(inpainter + (trends.size() > 1 ? "+" + trend_name(trend) : ""), options));
    }
  }
  for (const std::string& name : split_list(command.baselines)) {
    BaselineOptions options;
    try {
      options.method = baseline_from_name(name);
    } catch (const InvalidInput& error) {
      throw UsageError(std::string("--baselines: ") + error.what());
    }
    methods.push_back(baseline_method(options));
  }
  if (methods.empty()) throw UsageError("--inpainters, --baselines: no method to run");
  return methods;
}

// Throws InvalidInput unless `mesh` is a closed 2-manifold: the bench scores each fill against the
// surface punched out of a closed mesh, and counts the outputs that come back closed.
void check_closed(const Mesh& mesh, const std::string& file) {
  const ManifoldCheck check = check_manifold(mesh);
  if (check.closed_manifold()) return;
  throw InvalidInput(file + ": not a closed 2-manifold (" + std::to_string(check.boundary_loops) +
                     " boundary loops, " + std::to_string(check.nonmanifold_edges) +
                     " non-manifold edges, " + std::to_string(check.misoriented_edges) +
                     " misoriented edges, " + std::to_string(check.nonmanifold_vertices) +
                     " non-manifold vertices); the bench punches closed meshes (close it first: "
                     "rangefill repair --fill-all)");
}

// The report's view of punched hole h of `mesh`: its removed faces and the faces of the punched
// mesh within twice the truth's radius (from its centroid) of it.
HoleView hole_view(const Punched& mesh, int h) {
  HoleView view;
  view.truth = extract_faces(mesh.original, mesh.punched.holes[h].removed_faces);
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : view.truth.positions) centre += p;
  centre /= static_cast<double>(view.truth.positions.size());
  double radius = 0;
  for (const Vec3& p : view.truth.positions) radius = std::max(radius, (p - centre).norm());
  const Mesh& punched = mesh.punched.mesh;
  std::vector<int> near;
  for (int f = 0; f < punched.face_count(); ++f) {
    bool inside = true;
    for (int v : punched.triangles[f])
      inside &= (punched.positions[v] - centre).norm() < 2 * radius;
    if (inside) near.push_back(f);
  }
  view.surroundings = extract_faces(punched, near);
  return view;
}

// Appends `mesh` to `meshes`, its holes to `results`, and for each of them its mesh and its
// index there to `hole_of`.
void add_punched(Punched mesh, std::vector<Punched>& meshes, BenchResults& results,
                 std::vector<std::pair<int, int>>& hole_of) {
  for (size_t h = 0; h < mesh.punched.holes.size(); ++h) {
    BenchHole hole{mesh.name, static_cast<int>(h), mesh.mean_edge, mesh.punched.holes[h]};
    hole.hole.removed_faces.clear();
    results.holes.push_back(std::move(hole));
    hole_of.emplace_back(static_cast<int>(meshes.size()), static_cast<int>(h));
  }
  meshes.push_back(std::move(mesh));
}

// Each mesh punched with its own seed (add_punched).
std::vector<Punched> punch_meshes(const BenchCommand& command, const std::vector<fs::path>& files,
                                  BenchResults& results,
                                  std::vector<std::pair<int, int>>& hole_of) {
  PunchOptions punch_options = command.punch;
  punch_options.shapes.clear();
  for (const std::string& name : split_list(command.shapes)) {
    try {
      punch_options.shapes.push_back(shape_from_name(name));
    } catch (const InvalidInput& error) {
      throw UsageError(std::string("--shapes: ") + error.what());
    }
  }
  std::vector<Punched> meshes;
  for (const fs::path& file : files) {
    Punched mesh;
    mesh.name = file.filename().string();
    mesh.original = load_mesh(file.string());
    check_closed(mesh.original, file.string());
    mesh.mean_edge = mean_edge_length(mesh.original);
    PunchOptions options = punch_options;
    options.seed = seed_for_mesh(command.punch.seed, mesh.name);
    mesh.punched = punch_holes(mesh.original, options);
    mesh.loops = punched_loops(mesh.original, mesh.punched);
    add_punched(std::move(mesh), meshes, results, hole_of);
  }
  return meshes;
}

// --punched: the holes of the mesh kit's punch directories `dirs` (add_punched), each named by
// its directory, or by the directory above for one called "punch" (the kit's run_peers.sh
// layout: CASE/punch).
std::vector<Punched> read_punched(const std::vector<fs::path>& dirs, BenchResults& results,
                                  std::vector<std::pair<int, int>>& hole_of) {
  std::vector<Punched> meshes;
  for (const fs::path& dir : dirs) {
    KitPunch kit = read_kit_punch(dir);
    Punched mesh;
    const fs::path named = dir.filename() == "punch" ? dir.parent_path() : dir;
    mesh.name = named.filename().string();
    mesh.original = std::move(kit.original);
    check_closed(mesh.original, (dir / "holed.ply").string() + " with its holes' faces");
    mesh.punched = std::move(kit.punched);
    mesh.mean_edge = kit.mean_edge;
    mesh.loops = punched_loops(mesh.original, mesh.punched);
    add_punched(std::move(mesh), meshes, results, hole_of);
  }
  return meshes;
}

// --save: each punched mesh, its removed faces and each method's patches.
void save_meshes(const BenchCommand& command, const std::vector<Punched>& meshes,
                 const std::vector<BenchmarkMethod>& methods,
                 const std::vector<std::vector<Mesh>>& patch_parts,
                 const std::vector<fs::path>& inputs) {
  fs::create_directories(command.save);
  const int method_count = static_cast<int>(methods.size());
  for (size_t i = 0; i < meshes.size(); ++i) {
    const Punched& mesh = meshes[i];
    const std::string stem = fs::path(mesh.name).stem().string();
    std::vector<Mesh> truth;  // the removed faces, each marked with the hole it belongs to
    for (const PunchedHole& hole : mesh.punched.holes)
      truth.push_back(extract_faces(mesh.original, hole.removed_faces));
    const fs::path dir = command.save;
    write_output(serialize_mesh(mesh.punched.mesh, MeshFormat::ply), dir / (stem + "-punched.ply"),
                 inputs);
    write_output(serialize_mesh(marked_union(truth), MeshFormat::ply), dir / (stem + "-truth.ply"),
                 inputs);
    for (int k = 0; k < method_count; ++k) {
      write_output(serialize_mesh(marked_union(patch_parts[i * method_count + k]), MeshFormat::ply),
                   dir / (stem + "-" + methods[k].name + ".ply"), inputs);
    }
  }
}

// --out: holes.csv, summary.json, tables.md, the plots and report.html; `made_by` is the command
// that ran the jobs.
void write_report(const BenchCommand& command, const BenchResults& results,
                  const BenchSummary& summary, const std::string& table, const std::string& made_by,
                  const std::vector<fs::path>& inputs) {
  const fs::path dir = command.out;
  fs::create_directories(dir);
  json document = summary_json(results, summary);
  document["command"] = made_by;
  write_output(table, dir / "holes.csv", inputs);
  write_output(document.dump(2) + "\n", dir / "summary.json", inputs);
  write_output("# rangefill bench\n\n`" + made_by + "`\n\n" + markdown_tables(results, summary),
               dir / "tables.md", inputs);
  write_output(hausdorff_area_svg(results), dir / "hausdorff-vs-area.svg", inputs);
  write_output(class_ranking_svg(results, summary.area_classes, "hole area / d_m²"),
               dir / "ranks-by-area.svg", inputs);
  write_output(
      class_ranking_svg(results, surface_classes(summary), "curvature class, sharp feature"),
      dir / "ranks-by-curvature.svg", inputs);
  write_output(html_report(results, summary, made_by, command.tie), dir / "report.html", inputs);
}

// The runs' summary, the files of --csv and --out, and the summary printed.
int report_runs(const BenchCommand& command, const BenchResults& results,
                const std::string& made_by, const std::vector<fs::path>& inputs) {
  const BenchSummary summary = summarize(results, command.area_classes, command.tie);
  const std::string table = csv_table(results);
  if (!command.csv.empty()) write_output(table, command.csv, inputs);
  if (!command.out.empty()) write_report(command, results, summary, table, made_by, inputs);
  if (command.json) {
    print_json(summary_json(results, summary));
  } else {
    print_summary(results, summary, command);
  }
  return kOk;
}

// --- Shards: `--shard K/N --out DIR` runs jobs K, K + N, ... of the (hole, method) jobs in
// hole-major order and writes them to DIR/shard-K-of-N.json with what the merge checks; `--merge
// DIR...` reads the shards of every DIR and reports as the unsharded run would.

constexpr const char* kShardFormat = "rangefill bench shard 1";

// What decides the jobs and their scores: the shards of one run agree on it.
json bench_configuration(const BenchCommand& command, const std::vector<std::string>& names) {
  return {{"meshes", names},
          {"punched", !command.punched.empty()},
          {"holes_per_mesh", command.punch.holes},
          {"seed", command.punch.seed},
          {"min_radius", command.punch.min_radius},
          {"max_radius", command.punch.max_radius},
          {"shapes", command.shapes},
          {"spread", command.punch.spread},
          {"inpainters", command.inpainters},
          {"baselines", command.baselines},
          {"alpha", command.inpainting.mls.alpha},
          {"trends", command.trends},
          {"filler", command.filler},
          {"fallback", command.fallback},
          {"select", command.select},
          {"area_classes", command.area_classes},
          {"tie", command.tie}};
}

json hole_json(const BenchHole& hole) {
  const PunchedHole& h = hole.hole;
  return {{"mesh", hole.mesh},
          {"index", hole.index},
          {"mean_edge", hole.mean_edge},
          {"shape", shape_name(h.shape)},
          {"centre", h.centre},
          {"radius", h.radius},
          {"length", h.length},
          {"area", h.area},
          {"bending", h.bending},
          {"curvature", curvature_name(h.curvature)},
          {"sharp_feature", h.sharp_feature}};
}

BenchHole hole_from_json(const json& j) {
  BenchHole hole{j.at("mesh"), j.at("index"), j.at("mean_edge"), {}};
  PunchedHole& h = hole.hole;
  h.shape = shape_from_name(j.at("shape"));
  h.centre = j.at("centre");
  h.radius = j.at("radius");
  h.length = j.at("length");
  h.area = j.at("area");
  h.bending = j.at("bending");
  h.curvature = curvature_from_name(j.at("curvature"));
  h.sharp_feature = j.at("sharp_feature");
  return hole;
}

std::string shard_file_name(std::pair<int, int> shard) {
  return "shard-" + std::to_string(shard.first) + "-of-" + std::to_string(shard.second) + ".json";
}

void write_shard(const BenchCommand& command, const BenchResults& results,
                 const std::vector<std::string>& names, const std::vector<fs::path>& files,
                 std::pair<int, int> shard, const std::vector<int>& jobs,
                 const std::vector<ChildResult>& children) {
  json holes = json::array(), views = json::array(), runs = json::object();
  for (const BenchHole& hole : results.holes) holes.push_back(hole_json(hole));
  for (const HoleView& view : results.views) {
    views.push_back({mesh_json(view.surroundings), mesh_json(view.truth)});
  }
  for (size_t i = 0; i < jobs.size(); ++i) runs[std::to_string(jobs[i])] = job_entry(children[i]);
  const json document = {{"format", kShardFormat},
                         {"shard", {shard.first, shard.second}},
                         {"command", command_line()},
                         {"configuration", bench_configuration(command, names)},
                         {"methods", results.methods},
                         {"backends", results.backends},
                         {"holes", holes},
                         {"views", views},
                         {"runs", runs}};
  fs::create_directories(command.out);
  write_output(document.dump() + "\n", fs::path(command.out) / shard_file_name(shard), files);
  std::printf("shard %d/%d: %zu of %zu jobs (%zu holes × %zu methods) written to %s\n", shard.first,
              shard.second, jobs.size(), results.holes.size() * results.methods.size(),
              results.holes.size(), results.methods.size(),
              (fs::path(command.out) / shard_file_name(shard)).c_str());
}

// The shard files of `directories`, parsed, in name order within each.
std::vector<std::pair<fs::path, json>> read_shards(const std::vector<std::string>& directories) {
  std::vector<std::pair<fs::path, json>> shards;
  for (const std::string& directory : directories) {
    if (!fs::is_directory(directory)) throw IoError(directory + ": not a directory");
    std::vector<fs::path> files;
    for (const fs::directory_entry& entry : fs::directory_iterator(directory)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("shard-", 0) == 0 && entry.path().extension() == ".json") {
        files.push_back(entry.path());
      }
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
      json document = json::parse(read_file(file), nullptr, false);
      if (document.is_discarded() || !document.is_object() ||
          document.value("format", "") != kShardFormat) {
        throw InvalidInput(file.string() + ": not a shard file of rangefill bench");
      }
      shards.emplace_back(file, std::move(document));
    }
  }
  if (shards.empty()) throw InvalidInput("--merge: no shard-*.json file in " + join(directories));
  return shards;
}

// --merge: the shards checked (one run, each share once, every job there) and reported.
int merge_shards(const BenchCommand& command) {
  const std::vector<std::pair<fs::path, json>> shards = read_shards(command.merge);
  const json& first = shards.front().second;
  const int count = first.at("shard")[1];
  std::vector<int> seen(count, 0);
  json entries = json::object();
  for (const auto& [file, shard] : shards) {
    for (const char* key : {"configuration", "methods", "backends", "holes"}) {
      if (shard.at(key) != first.at(key)) {
        throw InvalidInput(file.string() + ": from another bench run than " +
                           shards.front().first.string() + " (its " + key + " differ)");
      }
    }
    const int k = shard.at("shard")[0];
    if (shard.at("shard")[1] != count || k < 0 || k >= count) {
      throw InvalidInput(file.string() + ": a shard of " + shard.at("shard")[1].dump() +
                         ", not of " + std::to_string(count));
    }
    if (seen[k]++) throw InvalidInput(file.string() + ": shard " + std::to_string(k) + " again");
    entries.update(shard.at("runs"));
  }
  std::vector<std::string> missing;
  for (int k = 0; k < count; ++k) {
    if (!seen[k]) missing.push_back(std::to_string(k));
  }
  if (!missing.empty()) {
    throw InvalidInput("--merge: shards " + join(missing) + " of " + std::to_string(count) +
                       " are missing");
  }

  BenchCommand merged = command;
  const json& configuration = first.at("configuration");
  merged.punch.holes = configuration.at("holes_per_mesh");
  merged.punch.seed = configuration.at("seed");
  if (configuration.value("punched", false)) {  // the summary names where the holes came from
    merged.punched = configuration.at("meshes").get<std::vector<std::string>>();
  }
  merged.area_classes = configuration.at("area_classes");
  merged.tie = configuration.at("tie");
  BenchResults results;
  results.methods = first.at("methods").get<std::vector<std::string>>();
  results.backends = first.at("backends");
  for (const json& hole : first.at("holes")) results.holes.push_back(hole_from_json(hole));
  const size_t method_count = results.methods.size();
  for (size_t h = 0; h < results.holes.size(); ++h) {
    results.runs.emplace_back();
    for (size_t m = 0; m < method_count; ++m) {
      const std::string job = std::to_string(h * method_count + m);
      if (!entries.contains(job)) throw InvalidInput("--merge: job " + job + " is in no shard");
      results.runs[h].push_back(run_from_entry(entries[job], results.holes[h]));
    }
    results.views.push_back({mesh_from_json(first.at("views").at(h).at(0)),
                             mesh_from_json(first.at("views").at(h).at(1))});
  }
  const std::string made_by = first.at("command").get<std::string>() + " (merged from " +
                              std::to_string(count) + " shards)";
  return report_runs(merged, results, made_by, {});
}

// The arguments that do not go together, before any work.
void check_bench_arguments(const BenchCommand& command) {
  if (!command.merge.empty() + !command.meshes.empty() + !command.punched.empty() != 1) {
    throw UsageError(
        "give --meshes (to punch them and run the jobs), --punched DIR... (to run them on holes "
        "the mesh kit punched) or --merge DIR... (to report on shards)");
  }
  if (!command.merge.empty() && command.out.empty()) throw UsageError("--merge needs --out DIR");
  if (!command.merge.empty() && (!command.save.empty() || !command.shard.empty())) {
    throw UsageError("--merge takes no --save or --shard");
  }
  if (!command.shard.empty()) {
    parse_shard(command.shard);
    if (command.out.empty()) throw UsageError("--shard needs --out DIR (where its jobs go)");
    if (!command.save.empty() || !command.csv.empty() || command.json) {
      throw UsageError(
          "--shard writes its jobs to --out; --save, --csv and --json go with --merge");
    }
  }
}

int run_bench(const BenchCommand& command) {
  check_bench_arguments(command);
  if (!command.merge.empty()) return merge_shards(command);
  const std::vector<BenchmarkMethod> methods = bench_methods(command);
  BenchResults results;
  for (const BenchmarkMethod& method : methods) results.methods.push_back(method.name);
  results.backends = backend_count(command);
  std::vector<std::pair<int, int>> hole_of;  // per benchmark hole: mesh, hole in it
  std::vector<fs::path> files;               // what the outputs must not overwrite
  std::vector<Punched> meshes;
  if (command.punched.empty()) {
    files = mesh_files(command.meshes);
    if (files.empty()) throw UsageError("--meshes: no mesh files found");
    meshes = punch_meshes(command, files, results, hole_of);
  } else {
    const std::vector<fs::path> dirs = kit_punch_dirs(command.punched);
    for (const fs::path& dir : dirs) files.push_back(dir / "holed.ply");
    meshes = read_punched(dirs, results, hole_of);
  }
  std::vector<std::string> names;
  for (const Punched& mesh : meshes) names.push_back(mesh.name);

  // One child process per hole and method, in that order (this shard's share of them).
  const int method_count = static_cast<int>(methods.size());
  std::vector<int> all_jobs(results.holes.size() * method_count);
  std::iota(all_jobs.begin(), all_jobs.end(), 0);
  const std::pair<int, int> shard =
      command.shard.empty() ? std::pair<int, int>{0, 1} : parse_shard(command.shard);
  const std::vector<int> jobs = shard_of(all_jobs, shard);
  const bool images = !command.out.empty(), patches = images || !command.save.empty();
  if (images) {
    for (const auto& [m, h] : hole_of) results.views.push_back(hole_view(meshes[m], h));
  }
  const bool progress = stderr_is_terminal();
  int finished = 0;
  const std::vector<ChildResult> children = run_in_children(
      static_cast<int>(jobs.size()), command.threads, command.timeout,
      [&](int i) {
        const auto [m, h] = hole_of[jobs[i] / method_count];
        const Punched& mesh = meshes[m];
        return run_json(run_method_on_hole(mesh.original, mesh.punched, h, mesh.loops[h],
                                           methods[jobs[i] % method_count], mesh.mean_edge),
                        images, patches);
      },
      [&](int i, const ChildResult&) {
        ++finished;
        if (!progress) return;
        const BenchHole& hole = results.holes[jobs[i] / method_count];
        std::fprintf(stderr, "\r\033[K[%d/%zu] %s hole %d: %s", finished, jobs.size(),
                     hole.mesh.c_str(), hole.index, methods[jobs[i] % method_count].name.c_str());
      });
  if (progress) std::fprintf(stderr, "\r\033[K");
  if (!command.shard.empty()) {
    write_shard(command, results, names, files, shard, jobs, children);
    return kOk;
  }

  std::vector<std::vector<Mesh>> patch_parts(meshes.size() * method_count);
  for (size_t h = 0; h < results.holes.size(); ++h) {
    results.runs.emplace_back();
    for (int k = 0; k < method_count; ++k) {
      results.runs[h].push_back(
          run_from_entry(job_entry(children[h * method_count + k]), results.holes[h]));
      patch_parts[hole_of[h].first * method_count + k].push_back(results.runs[h].back().patch);
    }
  }
  if (!command.save.empty()) save_meshes(command, meshes, methods, patch_parts, files);
  return report_runs(command, results, command_line(), files);
}

}  // namespace

void add_bench_command(CLI::App& app, Runner& runner) {
  auto command = std::make_shared<BenchCommand>();
  CLI::App* sub = app.add_subcommand(
      "bench",
      "Punch holes into closed meshes, fill them with each back-end and baseline, and "
      "measure (Perez et al., Section X)");
  sub->add_option("--meshes", command->meshes, "Closed meshes, or directories of them");
  sub->add_option("--punched", command->punched,
                  "Instead of --meshes: holes punched by the mesh evaluation kit's punch (its "
                  "output directories, or directories above them: holed.ply, gt_hole_<id>.ply, "
                  "holes.json), scored in the kit's d_m and curvature classes");
  sub->add_option("--holes-per-mesh", command->punch.holes, "Holes punched per mesh")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  sub->add_option("--seed", command->punch.seed, "Seed of the punching")->capture_default_str();
  sub->add_option("--min-radius", command->punch.min_radius,
                  "Smallest hole size (disk: radius; elongated: half-length), in d_m")
      ->capture_default_str();
  sub->add_option("--max-radius", command->punch.max_radius, "Largest hole size, in d_m")
      ->capture_default_str();
  sub->add_option("--shapes", command->shapes, "Hole shapes taken in turn: disk, elongated")
      ->capture_default_str();
  sub->add_flag("--spread,!--no-spread", command->punch.spread,
                "Look for each hole in turn where the surface is of low, medium or high curvature "
                "or on a sharp feature (default on)");
  sub->add_option("--inpainters", command->inpainters,
                  "Comma-separated back-ends (default: all, unless --baselines is given)");
  sub->add_option("--baselines", command->baselines,
                  "Comma-separated baselines: cgal-fair, cgal-triangulate (CGAL's Liepa)");
  sub->add_option("--alpha", command->inpainting.mls.alpha,
                  "mls: alpha of the weights exp(-alpha d^2)/d^2 (eq. 6), d in pixels")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  add_foe_inference_options(sub, command->inpainting);
  sub->add_option("--trends", command->trends,
                  "Comma-separated trends (none, plane, quadric, sphere, auto)")
      ->capture_default_str();
  sub->add_option("--filler", command->filler,
                  "fairing, plane or front (see rangefill repair --help); plane compares the "
                  "back-ends on every hole")
      ->capture_default_str()
      ->check(CLI::IsMember({"fairing", "plane", "front"}));
  sub->add_option("--fallback", command->fallback,
                  "fairing, plane, front, least-area in the order tried, or none")
      ->capture_default_str();
  sub->add_option("--select", command->select,
                  "Candidates of each back-end's band test (as repair --select; plane alone is the "
                  "method's own back-end; none when --filler or --fallback is given without it)")
      ->capture_default_str();
  sub->add_option("--threads", command->threads, "Holes filled at once (each in a process)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  sub->add_option("--timeout", command->timeout,
                  "Seconds one method may take on one hole before it counts as failed (0: none)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  sub->add_option("--area-classes", command->area_classes,
                  "Hole-area classes of equal width for the ranking by class (Table 5)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  sub->add_option("--tie", command->tie,
                  "Hausdorff distances within this many d_m of each other rank as equal")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  sub->add_option("--csv", command->csv, "Write one row per hole and method to this file");
  sub->add_option("--out", command->out,
                  "Write holes.csv, summary.json, tables.md, SVG plots and report.html here");
  sub->add_option("--save", command->save,
                  "Write each punched mesh, its removed faces (the ground truth) and each "
                  "method's patches here");
  sub->add_flag("--json", command->json, "Print the summary as JSON");
  sub->add_option("--shard", command->shard,
                  "K/N: run only jobs K, K+N, K+2N, ... of the (hole, method) jobs (0-based) and "
                  "write them to --out DIR as shard-K-of-N.json, for job arrays");
  sub->add_option("--merge", command->merge,
                  "Report on the shards in these directories (written by --shard) as the "
                  "unsharded run would, into --out DIR");
  sub->callback([command, sub, &runner] {
    command->app = sub;
    candidates_from_arguments(*sub, command->select,
                              FillerOptions());  // a bad name is a usage error
    runner = [command] { return run_bench(*command); };
  });
}

}  // namespace rangefill::cli
