#include "rangefill/pipeline.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include "rangefill/errors.h"

namespace rangefill {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<int> sorted_vertices(const BoundaryLoop& loop) {
  std::vector<int> vertices = loop.vertices;
  std::sort(vertices.begin(), vertices.end());
  return vertices;
}

bool within_size_limits(const BoundaryLoop& loop, const RepairOptions& options) {
  return (options.max_hole_edges <= 0 ||
          static_cast<int>(loop.vertices.size()) <= options.max_hole_edges) &&
         (options.max_hole_area <= 0 || loop.area <= options.max_hole_area);
}

// Runs task(i) for i in [0, count) on `threads` threads.
template <typename Task>
void parallel_for(int count, int threads, Task task) {
  threads = std::clamp(threads, 1, std::max(1, count));
  if (threads == 1) {
    for (int i = 0; i < count; ++i) task(i);
    return;
  }
  std::atomic<int> next{0};
  std::vector<std::thread> workers;
  for (int t = 0; t < threads; ++t) {
    workers.emplace_back([&] {
      for (int i = next++; i < count; i = next++) task(i);
    });
  }
  for (std::thread& worker : workers) worker.join();
}

}  // namespace

Fill fill_hole(const Mesh& mesh, const MeshTopology& topology, const HoleSet& holes,
               const BoundaryLoop& hole, const std::vector<Vec3>& vertex_normals, double mean_edge,
               const Inpainter& inpainter, const RepairOptions& options, HoleReport& report) {
  const Clock::time_point start = Clock::now();
  const std::string name = "hole " + std::to_string(hole.id);
  report.boundary_vertices = static_cast<int>(hole.vertices.size());
  report.area = hole.area;

  const Zone zone = grow_zone(mesh, topology, holes, hole, vertex_normals, mean_edge, options.zone);
  report.rings = zone.rings;
  report.zone_faces = static_cast<int>(zone.faces.size());
  report.other_holes = zone.other_holes;
  if (zone.faces.empty()) throw ProcessingError(name + ": the zone of interest is empty");

  const Projection projection = best_projection(mesh, topology, zone, hole, options.projection);
  if (projection.complex) {
    throw ProcessingError(name + ": complex hole: no plane tried (" +
                          std::to_string(projection.orientations_tried) +
                          ") sees its rim from the front with a simple boundary (Section VI-C)");
  }
  const Zone visible = visible_part(mesh, topology, zone, hole, projection.frame);
  report.zone_faces = static_cast<int>(visible.faces.size());

  RangeImage image =
      rasterize_zone(mesh, visible, hole, projection.frame, mean_edge, options.image);
  report.gap_pixels = fill_small_gaps(image).pixels;
  const cv::Mat mask = image.mask();
  report.image_size = image.depth.size();
  report.masked_pixels = cv::countNonZero(mask);

  const Trend trend = fit_trend(image, options.trend, options.trend_ring);
  report.trend = trend.kind;
  const cv::Mat trend_image = trend.image(image.depth.size());
  const cv::Mat residual = image.depth - trend_image;

  const Clock::time_point inpainting_start = Clock::now();
  cv::Mat restored;
  inpainter.inpaint(residual, mask, restored);
  report.inpainting_seconds = seconds_since(inpainting_start);
  restored += trend_image;
  if (options.on_images) options.on_images({report.id, image, restored});

  const Patch patch = back_project(mesh, hole, image, restored, options.back_projection);
  Fill fill = stitch(mesh, topology, hole, projection.frame, patch, triangulate_grid(patch));
  report.new_vertices = static_cast<int>(fill.points.size());
  report.new_faces = static_cast<int>(fill.triangles.size());
  report.filled = true;
  report.seconds = seconds_since(start);
  return fill;
}

std::array<long long, 3> merge_fill(Mesh& mesh, const Fill& fill, int hole_id) {
  const int boundary_size = static_cast<int>(fill.boundary.size());
  Rgb mean_color = Rgb::Zero();
  if (mesh.has_colors()) {
    for (int v : fill.boundary) mean_color += mesh.colors[v];
    mean_color /= static_cast<float>(std::max(1, boundary_size));
  }
  std::vector<int> mesh_id(fill.boundary);
  const int first_new = mesh.vertex_count();
  for (const Vec3& point : fill.points)
    mesh_id.push_back(add_vertex(mesh, point, hole_id, mean_color));

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

RepairResult repair(const Mesh& input, const RepairOptions& options) {
  RepairResult result;
  result.mesh = input;
  Mesh& mesh = result.mesh;
  const std::unique_ptr<Inpainter> inpainter =
      make_inpainter(options.inpainter, options.inpainting);
  MeshTopology topology = build_topology(mesh);
  const double mean_edge = mean_edge_length(mesh, topology);
  if (!(mean_edge > 0)) throw InvalidInput("repair: the mesh has no edges");
  result.restoration_matrix.push_back(
      {mesh.vertex_count(), static_cast<long long>(topology.edges.size()), mesh.face_count()});

  // Serialised callbacks: workers report one at a time.
  std::mutex callback_mutex;
  RepairOptions worker_options = options;
  if (options.on_images) {
    worker_options.on_images = [&](const HoleImages& images) {
      std::lock_guard<std::mutex> lock(callback_mutex);
      options.on_images(images);
    };
  }

  std::set<std::vector<int>> seen;       // loops already attempted or deliberately left open
  std::set<std::vector<int>> left_open;  // loops the options exclude
  int next_id = 0;
  for (int pass = 0; pass < options.passes; ++pass) {
    if (pass > 0) topology = build_topology(mesh);
    const HoleSet holes = find_holes(mesh, topology);
    const std::vector<Vec3> normals = vertex_normals_from_faces(mesh);
    std::vector<const BoundaryLoop*> selected;
    for (const BoundaryLoop& loop : holes.loops) {
      std::vector<int> key = sorted_vertices(loop);
      if (!seen.insert(key).second) continue;
      const bool named = std::count(options.holes.begin(), options.holes.end(), loop.id) > 0;
      const bool skipped_border = pass == 0 && options.holes.empty() &&
                                  options.skip_longest_loops && loop.longest_in_component;
      if (skipped_border) result.skipped_borders.push_back(loop.id);
      const bool chosen = (pass > 0 || named || (options.holes.empty() && !skipped_border)) &&
                          within_size_limits(loop, options);
      if (chosen) {
        selected.push_back(&loop);
      } else {
        left_open.insert(std::move(key));
      }
    }
    if (selected.empty()) break;

    const int id_base = next_id;
    std::vector<HoleReport> reports(selected.size());
    std::vector<std::optional<Fill>> fills(selected.size());
    parallel_for(static_cast<int>(selected.size()), options.threads, [&](int i) {
      const BoundaryLoop& loop = *selected[i];
      HoleReport& report = reports[i];
      report.id = id_base + loop.id;
      report.pass = pass;
      report.loop = loop.id;
      const Clock::time_point start = Clock::now();
      try {
        fills[i] = fill_hole(mesh, topology, holes, loop, normals, mean_edge, *inpainter,
                             worker_options, report);
      } catch (const std::exception& error) {
        report.failure = error.what();
        report.seconds = seconds_since(start);
      }
      if (options.on_hole) {
        std::lock_guard<std::mutex> lock(callback_mutex);
        options.on_hole(report);
      }
    });
    for (size_t i = 0; i < selected.size(); ++i) {
      if (fills[i]) result.restoration_matrix.push_back(merge_fill(mesh, *fills[i], reports[i].id));
      result.holes.push_back(std::move(reports[i]));
    }
    next_id = id_base + static_cast<int>(holes.loops.size());
  }

  topology = build_topology(mesh);
  for (const BoundaryLoop& loop : find_holes(mesh, topology).loops) {
    result.holes_left += left_open.count(sorted_vertices(loop)) == 0;
  }
  return result;
}

}  // namespace rangefill
