#include "rangefill/repair/pipeline.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <unordered_map>

#include "rangefill/core/errors.h"
#include "rangefill/core/parallel.h"
#include "rangefill/repair/fill_chain.h"

namespace rangefill {

std::vector<Rgb> boundary_colors(const Mesh& mesh, const std::vector<int>& boundary,
                                 const std::vector<Vec3>& points) {
  std::vector<Rgb> colors;
  colors.reserve(points.size());
  for (const Vec3& point : points) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double total = 0;
    for (int v : boundary) {
      const double squared = (mesh.positions[v] - point).squaredNorm();
      if (squared == 0) {  // on a boundary vertex: its colour
        sum = mesh.colors[v].cast<double>();
        total = 1;
        break;
      }
      sum += mesh.colors[v].cast<double>() / squared;
      total += 1 / squared;
    }
    colors.push_back(total > 0 ? Rgb((sum / total).cast<float>()) : Rgb::Zero());
  }
  return colors;
}

std::array<long long, 3> merge_fill(Mesh& mesh, const Fill& fill, int hole_id) {
  const int boundary_size = static_cast<int>(fill.boundary.size());
  std::vector<Rgb> colors(fill.points.size(), Rgb::Zero());
  if (mesh.has_colors()) {
    colors = fill.colors.size() == fill.points.size()
                 ? fill.colors
                 : boundary_colors(mesh, fill.boundary, fill.points);
  }
  std::vector<int> mesh_id(fill.boundary);
  const int first_new = mesh.vertex_count();
  for (size_t k = 0; k < fill.points.size(); ++k) {
    mesh_id.push_back(add_vertex(mesh, fill.points[k], hole_id, colors[k]));
  }

  std::set<std::pair<int, int>> edges;
  for (const Triangle& t : fill.triangles) {
    const Triangle mapped = {mesh_id[t[0]], mesh_id[t[1]], mesh_id[t[2]]};
    const int face = add_face(mesh, mapped, hole_id);
    for (int k = 0; k < 3; ++k) {
      edges.emplace(std::min(mapped[k], mapped[(k + 1) % 3]),
                    std::max(mapped[k], mapped[(k + 1) % 3]));
    }
    if (mesh.has_normals()) {
      for (int v : mapped) {
        if (v >= first_new) mesh.normals[v] += triangle_cross(mesh, face);
      }
    }
  }
  if (mesh.has_normals()) {
    for (int v = first_new; v < mesh.vertex_count(); ++v) mesh.normals[v].normalize();
  }
  return {static_cast<long long>(fill.points.size()),
          static_cast<long long>(edges.size()) - boundary_size,
          static_cast<long long>(fill.triangles.size())};
}

std::string open_reason_name(OpenReason reason) {
  switch (reason) {
    case OpenReason::border:
      return "border";
    case OpenReason::not_selected:
      return "not selected";
    case OpenReason::over_size_limit:
      return "over size limit";
    case OpenReason::failed:
      return "failed";
  }
  return "";
}

int RepairResult::open_count(OpenReason reason) const {
  return static_cast<int>(
      std::count_if(open_loops.begin(), open_loops.end(),
                    [&](const OpenLoop& loop) { return loop.reason == reason; }));
}

namespace {

bool within_size_limits(const BoundaryLoop& loop, const RepairOptions& options) {
  return (options.max_hole_edges <= 0 ||
          static_cast<int>(loop.vertices.size()) <= options.max_hole_edges) &&
         (options.max_hole_area <= 0 || loop.area <= options.max_hole_area);
}

// Why the options leave an input loop open; nullopt when it is to be filled.
std::optional<OpenReason> reason_left_open(const BoundaryLoop& loop, const RepairOptions& options) {
  if (!options.holes.empty()) {
    if (std::count(options.holes.begin(), options.holes.end(), loop.id) == 0) {
      return OpenReason::not_selected;
    }
  } else if (is_border(loop, options.border_share)) {
    return OpenReason::border;
  }
  if (!within_size_limits(loop, options)) return OpenReason::over_size_limit;
  return std::nullopt;
}

// The first vertex of `loop` that is in `sorted_vertices`, or -1.
int first_vertex_among(const BoundaryLoop& loop, const std::vector<int>& sorted_vertices) {
  for (int v : loop.vertices) {
    if (std::binary_search(sorted_vertices.begin(), sorted_vertices.end(), v)) return v;
  }
  return -1;
}

// What the passes of one repair carry from one to the next.
struct RepairState {
  std::set<std::vector<int>> seen;  // loops already attempted or deliberately left open
  // Input loops the options leave open, as they were judged (id, size, share in the input).
  std::map<std::vector<int>, OpenLoop> left_open;
  std::unordered_map<int, int> hole_of_vertex;  // boundary vertex -> id of the hole it bounded
  std::vector<int> unfillable;                  // the input's unfillable_vertices
  int next_id = 0;                              // the first id of this pass's new loops
};

// Step 1 of a pass: the loops to fill, each seen for the first time; in pass 0 the options may
// leave some open, which `state` keeps with their reason.
std::vector<const BoundaryLoop*> choose_loops(const HoleSet& holes, int pass,
                                              const RepairOptions& options, RepairState& state) {
  std::vector<const BoundaryLoop*> chosen;
  for (const BoundaryLoop& loop : holes.loops) {
    std::vector<int> key = sorted_vertices(loop);
    if (!state.seen.insert(key).second) continue;
    const std::optional<OpenReason> reason =
        pass == 0 ? reason_left_open(loop, options) : std::nullopt;
    if (reason) {
      state.left_open.emplace(std::move(key),
                              OpenLoop{loop.id, loop.id, static_cast<int>(loop.vertices.size()),
                                       loop.area, loop.area_share, *reason});
    } else {
      chosen.push_back(&loop);
    }
  }
  return chosen;
}

// A report per chosen loop. Ids: an input loop keeps its own; a loop found later (the rest of a
// partly filled complex hole) takes the id of the hole its vertices came from, so that one hole's
// patches share it.
std::vector<HoleReport> reports_for(const std::vector<const BoundaryLoop*>& loops, int pass,
                                    RepairState& state) {
  std::vector<HoleReport> reports(loops.size());
  for (size_t i = 0; i < loops.size(); ++i) {
    const BoundaryLoop& loop = *loops[i];
    HoleReport& report = reports[i];
    report.id = state.next_id + loop.id;
    for (int v : loop.vertices) {
      const auto origin = state.hole_of_vertex.find(v);
      if (origin != state.hole_of_vertex.end()) {
        report.id = origin->second;
        break;
      }
    }
    for (int v : loop.vertices) state.hole_of_vertex.emplace(v, report.id);
    report.pass = pass;
    report.loop = loop.id;
    report.boundary_vertices = static_cast<int>(loop.vertices.size());
    report.area = loop.area;
  }
  return reports;
}

// Step 2 of a pass: every chosen loop filled against the same surface, in parallel; a loop
// through an unfillable vertex is refused without a try.
std::vector<std::optional<Fill>> fill_pass(const SurfaceContext& surface,
                                           const std::vector<const BoundaryLoop*>& loops,
                                           const RepairOptions& options, bool last_pass,
                                           const RepairState& state,
                                           std::vector<HoleReport>& reports) {
  std::mutex callback_mutex;  // workers report one at a time
  ChainOptions chain_options;
  chain_options.zone = options.zone;
  chain_options.last_pass = last_pass;
  if (options.on_images) {
    chain_options.on_images = [&](const HoleImages& images) {
      std::lock_guard<std::mutex> lock(callback_mutex);
      options.on_images(images);
    };
  }
  std::vector<std::optional<Fill>> fills(loops.size());
  parallel_for(static_cast<int>(loops.size()), options.threads, [&](int i) {
    const BoundaryLoop& loop = *loops[i];
    HoleReport& report = reports[i];
    const auto start = std::chrono::steady_clock::now();
    const int defect = first_vertex_among(loop, state.unfillable);
    if (defect >= 0) {
      report.attempts.push_back(
          {"", "", {Refusal::nonmanifold_rim, "vertex " + std::to_string(defect)}});
      report.failure = "hole " + std::to_string(report.id) + ": " +
                       refusal_text(Refusal::nonmanifold_rim) + " (vertex " +
                       std::to_string(defect) + ")";
    } else {
      try {
        fills[i] = fill_by_selection(surface, loop, options.selection, options.chain, chain_options,
                                     report);
      } catch (const std::exception& error) {
        report.failure = error.what();
      }
    }
    report.seconds =  // the band tests included
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (options.on_hole) {
      std::lock_guard<std::mutex> lock(callback_mutex);
      options.on_hole(report);
    }
  });
  return fills;
}

// Loop `loop` of the repaired mesh, open: as the options left it (their reason, what they
// judged), or failed, with the hole its vertices came from and its `area_share` in the result.
OpenLoop open_loop(const Mesh& mesh, const BoundaryLoop& loop, int id, double area_share,
                   const RepairState& state) {
  OpenLoop open{id,        -1,         static_cast<int>(loop.vertices.size()),
                loop.area, area_share, OpenReason::failed};
  const auto known = state.left_open.find(sorted_vertices(loop));
  if (known != state.left_open.end()) {
    open = known->second;
    open.id = id;
    return open;
  }
  for (int v : loop.vertices) {
    const auto origin = state.hole_of_vertex.find(v);
    open.hole = origin != state.hole_of_vertex.end() ? origin->second : mesh.vertex_hole[v];
    if (open.hole != kOriginal) break;
  }
  return open;
}

// Every loop of the repaired mesh, found again in its whole topology.
std::vector<OpenLoop> open_loops_of(const Mesh& mesh, const RepairState& state) {
  std::vector<OpenLoop> open_loops;
  for (const BoundaryLoop& loop : find_holes(mesh, build_topology(mesh)).loops) {
    open_loops.push_back(open_loop(mesh, loop, loop.id, loop.area_share, state));
  }
  return open_loops;
}

// Whether the loops of the mesh after the last pass follow from that pass's: each fill merged
// closed its own loop and no loop touches another (a pinch) or runs into a non-manifold edge.
bool loops_follow_from_pass(const HoleSet& holes, bool next_pass) {
  return !next_pass && holes.pinched_vertices.empty() && holes.open_boundary_edges == 0;
}

double fill_area(const Mesh& mesh, const Fill& fill) {
  const int boundary_size = static_cast<int>(fill.boundary.size());
  const auto position = [&](int v) -> const Vec3& {
    return v < boundary_size ? mesh.positions[fill.boundary[v]] : fill.points[v - boundary_size];
  };
  double area = 0;
  for (const Triangle& t : fill.triangles) {
    area += 0.5 * (position(t[1]) - position(t[0])).cross(position(t[2]) - position(t[0])).norm();
  }
  return area;
}

// Every loop of the repaired mesh when loops_follow_from_pass: the last pass's loops but those
// its fills closed, in their order (find_holes numbers loops by their first half-edge, which faces
// appended at other loops leave alone), each component's area grown by its fills'. The whole
// mesh's topology is not built again.
std::vector<OpenLoop> open_loops_after_pass(const Mesh& mesh, const HoleSet& holes,
                                            const std::vector<const BoundaryLoop*>& loops,
                                            const std::vector<std::optional<Fill>>& fills,
                                            const RepairState& state) {
  std::vector<double> component_areas = holes.component_areas;
  std::set<int> closed;
  for (size_t i = 0; i < loops.size(); ++i) {
    if (!fills[i]) continue;
    closed.insert(loops[i]->id);
    component_areas[loops[i]->component] += fill_area(mesh, *fills[i]);
  }
  std::vector<OpenLoop> open_loops;
  for (const BoundaryLoop& loop : holes.loops) {
    if (closed.count(loop.id)) continue;
    const double total = component_areas[loop.component];
    open_loops.push_back(open_loop(mesh, loop, static_cast<int>(open_loops.size()),
                                   total > 0 ? loop.area / total : 0, state));
  }
  return open_loops;
}

// A fill set aside: it would intersect the fill of hole `other`, merged before it
// in this pass. Its loop is tried again in the next pass, against the merged mesh.
void defer_fill(const BoundaryLoop& loop, int other, RepairState& state, HoleReport& report) {
  state.seen.erase(sorted_vertices(loop));
  report.attempts.push_back(
      {report.filler,
       report.method,
       {Refusal::intersects, "with the fill of hole " + std::to_string(other) + " of its pass"}});
  report.failure = "hole " + std::to_string(report.id) + ": " + report.method +
                   ": its fill would intersect the fill of hole " + std::to_string(other);
  report.filled = false;
  report.filler.clear();
  report.method.clear();
  report.new_vertices = report.new_faces = 0;
}

// Step 3 of a pass: the fills merged in hole order (Section IX), the same at any thread count; a
// fill that would intersect one merged before it waits for the next pass. Returns whether the
// next pass has work: a loop deferred, or the rest of a loop filled in part (a fill whose boundary
// is not its loop); otherwise every loop is closed or known to stay open.
bool merge_pass(const std::vector<const BoundaryLoop*>& loops,
                const std::vector<std::optional<Fill>>& fills, std::vector<HoleReport>& reports,
                RepairState& state, RepairResult& result) {
  int new_vertices = 0, new_faces = 0;
  for (const std::optional<Fill>& fill : fills) {
    if (!fill) continue;
    new_vertices += static_cast<int>(fill->points.size());
    new_faces += static_cast<int>(fill->triangles.size());
  }
  reserve_more(result.mesh, new_vertices, new_faces);
  std::vector<size_t> merged;
  bool next_pass = false;
  for (size_t i = 0; i < loops.size(); ++i) {
    if (fills[i]) {
      const auto clash = std::find_if(merged.begin(), merged.end(), [&](size_t j) {
        return fills_intersect(result.mesh, *fills[i], *fills[j]);  // merging only appends
      });
      if (clash == merged.end()) {
        result.restoration_matrix.push_back(merge_fill(result.mesh, *fills[i], reports[i].id));
        merged.push_back(i);
        next_pass = next_pass || fills[i]->boundary != loops[i]->vertices;
      } else {
        defer_fill(*loops[i], reports[*clash].id, state, reports[i]);
        next_pass = true;
      }
    }
    result.holes.push_back(std::move(reports[i]));
  }
  return next_pass;
}

// A pass's loops, those chosen and their fills.
struct PassFills {
  HoleSet holes;
  std::vector<const BoundaryLoop*> chosen;  // into holes.loops
  std::vector<HoleReport> reports;
  std::vector<std::optional<Fill>> fills;
};

// Steps 1 and 2 of a pass: the mesh's loops, those chosen and their fills. The surface's topology
// and intersection index are freed on return, before merging the fills grows the mesh's arrays
// (the mesh, its topology and its grown arrays at once would be a large repair's peak of memory).
// The first pass also takes d_m, the restoration matrix's first row, the defects and the
// unfillable vertices.
PassFills fill_loops(const Mesh& mesh, int pass, const RepairOptions& options, double& mean_edge,
                     RepairState& state, RepairResult& result) {
  SurfaceContext surface(mesh, mean_edge);
  if (pass == 0) {
    mean_edge = surface.mean_edge;
    if (!(mean_edge > 0)) throw InvalidInput("repair: the mesh has no edges");
    result.restoration_matrix.push_back(
        {mesh.vertex_count(), surface.topology.edge_count, mesh.face_count()});
    result.defects = find_defects(mesh, surface.topology);
    state.unfillable = unfillable_vertices(mesh, surface.topology);
    const int loops = static_cast<int>(surface.holes.loops.size());
    for (int id : options.holes) {
      if (id < 0 || id >= loops) {
        throw InvalidInput("repair: there is no boundary loop " + std::to_string(id) +
                           " to fill (the mesh has " + std::to_string(loops) + ")");
      }
    }
  }
  PassFills filled;
  filled.chosen = choose_loops(surface.holes, pass, options, state);
  filled.reports = reports_for(filled.chosen, pass, state);
  filled.fills =
      fill_pass(surface, filled.chosen, options, pass == options.passes - 1, state, filled.reports);
  filled.holes = std::move(surface.holes);  // the loops stay where `chosen` points
  return filled;
}

}  // namespace

RepairResult repair(const Mesh& input, const RepairOptions& options) {
  return repair(Mesh(input), options);
}

RepairResult repair(Mesh&& input, const RepairOptions& options) {
  RepairResult result;
  result.mesh = std::move(input);
  Mesh& mesh = result.mesh;
  double mean_edge = 0;  // the input's d_m, used in every pass
  RepairState state;
  for (int pass = 0; pass < options.passes; ++pass) {
    PassFills filled = fill_loops(mesh, pass, options, mean_edge, state, result);
    const bool next_pass = merge_pass(filled.chosen, filled.fills, filled.reports, state, result);
    state.next_id += static_cast<int>(filled.holes.loops.size());
    if (loops_follow_from_pass(filled.holes, next_pass)) {
      result.open_loops =
          open_loops_after_pass(mesh, filled.holes, filled.chosen, filled.fills, state);
      return result;
    }
    if (!next_pass) break;  // the next pass would find no loop to choose
  }
  result.open_loops = open_loops_of(mesh, state);
  return result;
}

}  // namespace rangefill
