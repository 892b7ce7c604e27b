#include "rangefill/repair/pipeline.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <set>
#include <unordered_map>

#include "rangefill/core/errors.h"
#include "rangefill/core/parallel.h"
#include "rangefill/repair/complex_hole.h"
#include "rangefill/repair/front.h"
#include "rangefill/repair/loop_patch.h"

namespace rangefill {

SurfaceContext::SurfaceContext(const Mesh& surface_mesh, double mean_edge_length)
    : mesh(surface_mesh),
      topology(build_topology(surface_mesh)),
      holes(find_holes(surface_mesh, topology)),
      normals(vertex_normals_from_faces(surface_mesh)),
      mean_edge(mean_edge_length > 0 ? mean_edge_length
                                     : rangefill::mean_edge_length(surface_mesh, topology)),
      faces(surface_mesh) {}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Seconds since `start`, which moves on to now.
double lap(Clock::time_point& start) {
  const Clock::time_point now = Clock::now();
  const double seconds = std::chrono::duration<double>(now - start).count();
  start = now;
  return seconds;
}

bool within_size_limits(const BoundaryLoop& loop, const RepairOptions& options) {
  return (options.max_hole_edges <= 0 ||
          static_cast<int>(loop.vertices.size()) <= options.max_hole_edges) &&
         (options.max_hole_area <= 0 || loop.area <= options.max_hole_area);
}

// The edges of `hole` that no face borders, in the frame's x, y: the chord closing a part of a
// complex hole (Section VI-C).
std::vector<std::array<Vec2, 2>> chords_in_frame(const SurfaceContext& surface,
                                                 const BoundaryLoop& hole, const Frame& frame) {
  std::vector<std::array<Vec2, 2>> chords;
  const size_t n = hole.vertices.size();
  for (size_t k = 0; k < n; ++k) {
    const int a = hole.vertices[k], b = hole.vertices[(k + 1) % n];
    if (find_halfedge(surface.mesh, surface.topology, a, b) < 0) {
      chords.push_back({frame.to_local(surface.mesh.positions[a]).head<2>(),
                        frame.to_local(surface.mesh.positions[b]).head<2>()});
    }
  }
  return chords;
}

// A fill triangle meets a face of the surface or a non-adjacent fill triangle.
bool fill_intersects(const SurfaceContext& surface, const Fill& fill) {
  const int boundary_size = static_cast<int>(fill.boundary.size());
  Mesh own;  // the fill alone, its boundary first
  for (int v : fill.boundary) own.positions.push_back(surface.mesh.positions[v]);
  own.positions.insert(own.positions.end(), fill.points.begin(), fill.points.end());
  own.triangles = fill.triangles;
  for (const Triangle& t : fill.triangles) {
    Triangle corners;
    for (int k = 0; k < 3; ++k) corners[k] = t[k] < boundary_size ? fill.boundary[t[k]] : -1;
    if (!surface.faces
             .intersecting_faces(own.positions[t[0]], own.positions[t[1]], own.positions[t[2]],
                                 corners)
             .empty()) {
      return true;
    }
  }
  std::vector<int> all(own.triangles.size());
  std::iota(all.begin(), all.end(), 0);
  return count_self_intersections(own, all) > 0;
}

// The trend of `values` (over the known pixels of `labels`; heights of `height_unit` pixels, or
// 0) removed, the residual inpainted under the hole mask, the trend added back. `fitted` receives
// the trend actually fitted.
cv::Mat inpaint_residual(const cv::Mat& values, const cv::Mat& labels, const cv::Mat& mask,
                         const Inpainter& inpainter, const RepairOptions& options,
                         double height_unit, TrendKind& fitted) {
  const Trend trend = fit_trend(values, labels, options.trend, options.trend_ring, height_unit);
  fitted = trend.kind;
  const cv::Mat trend_image = trend.image(values.size());
  // Outside the zone the image holds the nearest zone value, no surface: there the residual is 0
  // (the trend is the best guess), else back-ends that read beyond the rim (mls) take the gap
  // between a flat extension and a curved trend for surface.
  cv::Mat residual = values - trend_image, restored;
  residual.setTo(0, labels == kOutsidePixel);
  inpainter.inpaint(residual, mask, restored);
  return restored + trend_image;
}

// Wang & Oliveira, Section 4.4: the colour channels inpainted as images, each like depth.
cv::Mat inpaint_colors(const RangeImage& image, const cv::Mat& mask, const Inpainter& inpainter,
                       const RepairOptions& options) {
  std::vector<cv::Mat> channels;
  cv::split(image.color, channels);
  for (cv::Mat& channel : channels) {
    TrendKind fitted = TrendKind::none;
    channel = inpaint_residual(channel, image.labels, mask, inpainter, options, 0, fitted);
  }
  cv::Mat color;
  cv::merge(channels, color);
  return color;
}

// Sections VI–VIII on one plane: range image, trend, inpainting, back-projection, stitching.
Fill fill_through_plane(const SurfaceContext& surface, const BoundaryLoop& hole, const Zone& zone,
                        const Frame& frame, const Inpainter& inpainter,
                        const RepairOptions& options, HoleReport& report) {
  const Mesh& mesh = surface.mesh;
  const MeshTopology& topology = surface.topology;
  Clock::time_point stage = Clock::now();
  const Zone visible = visible_part(mesh, topology, zone, hole, frame);
  report.zone_faces = static_cast<int>(visible.faces.size());

  RangeImage image = rasterize_zone(mesh, visible, hole, frame, surface.mean_edge, options.image);
  report.gap_pixels = fill_small_gaps(image).pixels;
  report.rim_support = rim_support(image, chords_in_frame(surface, hole, frame));
  if (report.rim_support < options.min_rim_support) {
    throw ProcessingError("hole " + std::to_string(hole.id) + ": the plane sees only " +
                          std::to_string(static_cast<int>(100 * report.rim_support)) +
                          "% of the hole's surroundings");
  }
  const cv::Mat mask = image.mask();
  report.image_size = image.depth.size();
  report.masked_pixels = cv::countNonZero(mask);

  report.stages.image += lap(stage);

  const cv::Mat restored = inpaint_residual(image.depth, image.labels, mask, inpainter, options,
                                            1 / (image.depth_scale * image.step), report.trend);
  const cv::Mat restored_color =
      image.color.empty() ? cv::Mat() : inpaint_colors(image, mask, inpainter, options);
  report.stages.inpainting += lap(stage);
  if (options.on_images) options.on_images({report.id, image, restored});

  stage = Clock::now();
  Patch patch = back_project(mesh, hole, image, restored, options.back_projection);
  if (!restored_color.empty()) patch.colors = patch_colors(patch, restored_color);
  Fill fill = stitch(mesh, topology, hole, frame, patch, triangulate_grid(patch));
  report.stages.stitching += lap(stage);
  const bool intersects = fill_intersects(surface, fill);
  report.stages.checking += lap(stage);
  if (intersects) {
    throw ProcessingError("hole " + std::to_string(hole.id) +
                          ": the fill would intersect the surface or itself");
  }
  return fill;
}

// Sections VI–VIII on each plane in turn; the first fill accepted wins, the first refusal is kept.
std::optional<Fill> fill_through_planes(const SurfaceContext& surface, const BoundaryLoop& loop,
                                        const Zone& zone, const std::vector<Projection>& planes,
                                        const Inpainter& inpainter, const RepairOptions& options,
                                        HoleReport& report, std::string& failure) {
  for (const Projection& projection : planes) {
    try {
      return fill_through_plane(surface, loop, zone, projection.frame, inpainter, options, report);
    } catch (const ProcessingError& error) {
      if (failure.empty()) failure = error.what();
    }
  }
  return std::nullopt;
}

// Section VI-C: a part of a complex hole, through the planes of that part and its own zone.
std::optional<Fill> fill_part_through_planes(const SurfaceContext& surface,
                                             const BoundaryLoop& hole, const Frame& best_frame,
                                             const Inpainter& inpainter,
                                             const RepairOptions& options, HoleReport& report,
                                             std::string& failure) {
  for (const BoundaryLoop& part :
       split_complex_hole(surface.mesh, surface.topology, hole, best_frame)) {
    const Zone zone = grow_zone(surface.mesh, surface.topology, surface.holes, part,
                                surface.normals, surface.mean_edge, options.zone);
    const std::vector<Projection> planes =
        find_projections(surface.mesh, surface.topology, zone, part, options.projection).planes;
    if (auto fill =
            fill_through_planes(surface, part, zone, planes, inpainter, options, report, failure)) {
      return fill;
    }
  }
  return std::nullopt;
}

// Tekumalla & Cohen: the advancing front over an MLS surface of the zone's vertices.
Fill fill_through_front(const SurfaceContext& surface, const BoundaryLoop& hole, const Zone& zone,
                        const RepairOptions& options) {
  std::vector<Vec3> samples, normals;
  for (int v : zone.vertices) {
    samples.push_back(surface.mesh.positions[v]);
    normals.push_back(surface.normals[v]);
  }
  Fill fill =
      fill_by_front(surface.mesh, surface.topology, surface.faces, hole,
                    MlsSurface(std::move(samples), std::move(normals), options.mls), options.front);
  validate_fill(surface.mesh, surface.topology, hole, fill);
  if (fill_intersects(surface, fill)) {
    throw ProcessingError("hole " + std::to_string(hole.id) +
                          ": the front's fill would intersect the surface or itself");
  }
  return fill;
}

// The last resort: the hole's own loop triangulated without new vertices (what MeshLab's Close
// Holes does): by Liepa's weight, whose dihedral angles against the faces outside keep the patch
// from folding into the surface, else by least area avoiding the chords the mesh has; the first
// that is manifold and free of intersections. `method` receives which.
Fill fill_by_loop_patch(const SurfaceContext& surface, const BoundaryLoop& hole,
                        std::string& method) {
  const int n = static_cast<int>(hole.vertices.size());
  std::vector<Vec3> loop, third_points;
  for (int k = 0; k < n; ++k) {
    const int a = hole.vertices[k], b = hole.vertices[(k + 1) % n];
    loop.push_back(surface.mesh.positions[a]);
    const int along = find_halfedge(surface.mesh, surface.topology, a, b);
    if (along < 0) throw ProcessingError("hole " + std::to_string(hole.id) + ": not a border loop");
    // The corner of the face outside opposite the edge: where its previous half-edge starts.
    const int third = surface.mesh.triangles[halfedge_face(along)][prev_halfedge(along) % 3];
    third_points.push_back(surface.mesh.positions[third]);
  }
  Fill fill;
  fill.boundary = hole.vertices;
  std::string refusal;
  auto accepted = [&](std::vector<Triangle> triangles) {
    fill.triangles = std::move(triangles);
    try {
      if (fill.triangles.empty()) throw ProcessingError("no triangulation");
      validate_fill(surface.mesh, surface.topology, hole, fill);
      if (fill_intersects(surface, fill)) {
        throw ProcessingError("it would intersect the surface or itself");
      }
      return true;
    } catch (const ProcessingError& error) {
      refusal += std::string(refusal.empty() ? "" : "; ") + method + ": " + error.what();
      return false;
    }
  };
  method = "Liepa";
  if (accepted(triangulate_loop_liepa(loop, third_points))) return fill;
  std::set<std::pair<int, int>> forbidden;  // chords the mesh already has
  for (size_t i = 0; i < hole.vertices.size(); ++i) {
    for (size_t j = i + 2; j < hole.vertices.size(); ++j) {
      const int a = hole.vertices[i], b = hole.vertices[j];
      if (find_halfedge(surface.mesh, surface.topology, a, b) >= 0 ||
          find_halfedge(surface.mesh, surface.topology, b, a) >= 0) {
        forbidden.emplace(static_cast<int>(i), static_cast<int>(j));
      }
    }
  }
  method = "least area";
  if (accepted(triangulate_loop_least_area(loop, forbidden))) return fill;
  throw ProcessingError("hole " + std::to_string(hole.id) + ": no patch of its loop: " + refusal);
}

}  // namespace

Fill fill_hole(const SurfaceContext& surface, const BoundaryLoop& hole, const Inpainter& inpainter,
               const RepairOptions& options, HoleReport& report) {
  const Clock::time_point start = Clock::now();
  const std::string name = "hole " + std::to_string(hole.id);

  Clock::time_point stage = start;
  const Zone zone = grow_zone(surface.mesh, surface.topology, surface.holes, hole, surface.normals,
                              surface.mean_edge, options.zone);
  report.stages.zone = lap(stage);
  report.rings = zone.rings;
  report.zone_faces = static_cast<int>(zone.faces.size());
  report.other_holes = zone.other_holes;
  if (zone.faces.empty()) throw ProcessingError(name + ": the zone of interest is empty");

  // The planes on the whole hole, then the advancing front, then the planes on a part of it
  // (VI-C): a part leaves the rest to the next pass, the front closes the hole in one go.
  std::string failure;
  std::optional<Fill> fill;
  ProjectionSearch search;
  if (options.filler == Filler::plane) {
    report.method = "plane";
    search = find_projections(surface.mesh, surface.topology, zone, hole, options.projection);
    report.stages.planes = lap(stage);
    fill = fill_through_planes(surface, hole, zone, search.planes, inpainter, options, report,
                               failure);
    if (!fill && failure.empty()) {
      failure = name + ": complex hole: no plane tried (" +
                std::to_string(search.orientations_tried) +
                ") sees its rim from the front with a simple boundary (Section VI-C)";
    }
  }
  if (!fill && (options.filler == Filler::front || options.fallback_front)) {
    try {
      report.method = "front";
      stage = Clock::now();
      fill = fill_through_front(surface, hole, zone, options);
      report.stages.front = lap(stage);
    } catch (const ProcessingError& error) {
      failure += (failure.empty() ? "" : "; ") + std::string(error.what());
    }
  }
  bool in_part = false;
  if (!fill && options.filler == Filler::plane) {
    report.method = "plane, in part";
    fill = fill_part_through_planes(surface, hole, search.best_frame, inpainter, options, report,
                                    failure);
    in_part = fill.has_value();
  }
  // In the last pass the rest of a part would stay open: a patch of the whole loop comes first.
  const bool last_pass = report.pass == options.passes - 1;
  if ((!fill || (in_part && last_pass)) && options.fallback_least_area) {
    const std::string part_method = report.method;
    try {
      fill = fill_by_loop_patch(surface, hole, report.method);
    } catch (const ProcessingError& error) {
      failure += (failure.empty() ? "" : "; ") + std::string(error.what());
      report.method = part_method;
    }
  }
  if (!fill) throw ProcessingError(failure);
  report.new_vertices = static_cast<int>(fill->points.size());
  report.new_faces = static_cast<int>(fill->triangles.size());
  report.filled = true;
  report.seconds = seconds_since(start);
  return std::move(*fill);
}

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

}  // namespace

RepairResult repair(const Mesh& input, const RepairOptions& options) {
  RepairResult result;
  result.mesh = input;
  Mesh& mesh = result.mesh;
  const std::unique_ptr<Inpainter> inpainter =
      make_inpainter(options.inpainter, options.inpainting);
  double mean_edge = 0;         // the input's d_m, used in every pass
  std::vector<int> unfillable;  // the input's unfillable_vertices

  // Serialised callbacks: workers report one at a time.
  std::mutex callback_mutex;
  RepairOptions worker_options = options;
  if (options.on_images) {
    worker_options.on_images = [&](const HoleImages& images) {
      std::lock_guard<std::mutex> lock(callback_mutex);
      options.on_images(images);
    };
  }

  std::set<std::vector<int>> seen;  // loops already attempted or deliberately left open
  // Input loops the options leave open, as they were judged (id, size, share in the input).
  std::map<std::vector<int>, OpenLoop> left_open;
  std::unordered_map<int, int> hole_of_vertex;  // boundary vertex -> id of the hole it bounded
  int next_id = 0;
  for (int pass = 0; pass < options.passes; ++pass) {
    const SurfaceContext surface(mesh, mean_edge);
    if (pass == 0) {
      mean_edge = surface.mean_edge;
      if (!(mean_edge > 0)) throw InvalidInput("repair: the mesh has no edges");
      result.restoration_matrix.push_back({mesh.vertex_count(),
                                           static_cast<long long>(surface.topology.edges.size()),
                                           mesh.face_count()});
      result.defects = find_defects(mesh, surface.topology);
      unfillable = unfillable_vertices(mesh, surface.topology);
      const int loops = static_cast<int>(surface.holes.loops.size());
      for (int id : options.holes) {
        if (id < 0 || id >= loops) {
          throw InvalidInput("repair: there is no boundary loop " + std::to_string(id) +
                             " to fill (the mesh has " + std::to_string(loops) + ")");
        }
      }
    }
    std::vector<const BoundaryLoop*> selected;
    for (const BoundaryLoop& loop : surface.holes.loops) {
      std::vector<int> key = sorted_vertices(loop);
      if (!seen.insert(key).second) continue;
      const std::optional<OpenReason> reason =
          pass == 0 ? reason_left_open(loop, options) : std::nullopt;
      if (reason) {
        left_open.emplace(std::move(key),
                          OpenLoop{loop.id, loop.id, static_cast<int>(loop.vertices.size()),
                                   loop.area, loop.area_share, *reason});
      } else {
        selected.push_back(&loop);
      }
    }
    if (selected.empty()) break;

    // Ids: an input loop keeps its own; a loop found later (the rest of a partly filled complex
    // hole) takes the id of the hole its vertices came from, so one hole's patches share it.
    std::vector<HoleReport> reports(selected.size());
    for (size_t i = 0; i < selected.size(); ++i) {
      const BoundaryLoop& loop = *selected[i];
      HoleReport& report = reports[i];
      report.id = next_id + loop.id;
      for (int v : loop.vertices) {
        const auto origin = hole_of_vertex.find(v);
        if (origin != hole_of_vertex.end()) {
          report.id = origin->second;
          break;
        }
      }
      for (int v : loop.vertices) hole_of_vertex.emplace(v, report.id);
      report.pass = pass;
      report.loop = loop.id;
      report.boundary_vertices = static_cast<int>(loop.vertices.size());
      report.area = loop.area;
    }
    std::vector<std::optional<Fill>> fills(selected.size());
    parallel_for(static_cast<int>(selected.size()), options.threads, [&](int i) {
      const BoundaryLoop& loop = *selected[i];
      HoleReport& report = reports[i];
      const Clock::time_point start = Clock::now();
      const int defect = first_vertex_among(loop, unfillable);
      if (defect >= 0) {
        report.failure = "hole " + std::to_string(report.id) +
                         ": touches a non-manifold edge or vertex (vertex " +
                         std::to_string(defect) + ")";
      } else {
        try {
          fills[i] = fill_hole(surface, loop, *inpainter, worker_options, report);
        } catch (const std::exception& error) {
          report.failure = error.what();
        }
      }
      if (!report.filled) report.seconds = seconds_since(start);
      if (options.on_hole) {
        std::lock_guard<std::mutex> lock(callback_mutex);
        options.on_hole(report);
      }
    });
    for (size_t i = 0; i < selected.size(); ++i) {
      if (fills[i]) result.restoration_matrix.push_back(merge_fill(mesh, *fills[i], reports[i].id));
      result.holes.push_back(std::move(reports[i]));
    }
    next_id += static_cast<int>(surface.holes.loops.size());
  }

  // Every loop of the result: left open by the options, or to be filled and not.
  for (const BoundaryLoop& loop : find_holes(mesh, build_topology(mesh)).loops) {
    OpenLoop open{
        loop.id,           -1, static_cast<int>(loop.vertices.size()), loop.area, loop.area_share,
        OpenReason::failed};
    const auto known = left_open.find(sorted_vertices(loop));
    if (known != left_open.end()) {
      open = known->second;
      open.id = loop.id;
    } else {
      for (int v : loop.vertices) {
        const auto origin = hole_of_vertex.find(v);
        open.hole = origin != hole_of_vertex.end() ? origin->second : mesh.vertex_hole[v];
        if (open.hole != kOriginal) break;
      }
    }
    result.open_loops.push_back(open);
  }
  return result;
}

}  // namespace rangefill
