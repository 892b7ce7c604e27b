#include "rangefill/repair/fill_chain.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <numeric>
#include <set>

#include "rangefill/core/errors.h"
#include "rangefill/repair/complex_hole.h"
#include "rangefill/repair/loop_patch.h"
#include "rangefill/repair/patch_angles.h"
#include "rangefill/repair/stitch.h"

namespace rangefill {

std::string strategy_name(Strategy strategy) {
  switch (strategy) {
    case Strategy::plane:
      return "plane";
    case Strategy::front:
      return "front";
    case Strategy::plane_in_part:
      return "plane, in part";
    case Strategy::liepa:
      return "Liepa";
    case Strategy::least_area:
      return "least area";
    case Strategy::fairing:
      return "fairing";
  }
  return "";
}

std::string filler_name(Filler filler) {
  switch (filler) {
    case Filler::plane:
      return "plane";
    case Filler::front:
      return "front";
    case Filler::fairing:
      return "fairing";
  }
  return "";
}

Filler filler_from_name(const std::string& name) {
  for (Filler filler : {Filler::plane, Filler::front, Filler::fairing}) {
    if (name == filler_name(filler)) return filler;
  }
  throw InvalidInput("unknown filler '" + name + "' (expected plane, front or fairing)");
}

std::vector<Strategy> strategy_chain(Filler filler, const std::string& fallbacks) {
  std::vector<Strategy> chain = {filler == Filler::plane   ? Strategy::plane
                                 : filler == Filler::front ? Strategy::front
                                                           : Strategy::fairing};
  const auto add = [&](std::initializer_list<Strategy> strategies) {  // each strategy once
    if (std::find(chain.begin(), chain.end(), *strategies.begin()) == chain.end()) {
      chain.insert(chain.end(), strategies);
    }
  };
  for (size_t start = 0; fallbacks != "none" && start <= fallbacks.size();) {
    const size_t end = std::min(fallbacks.find(',', start), fallbacks.size());
    const std::string item = fallbacks.substr(start, end - start);
    if (item == "plane") {
      add({Strategy::plane});
    } else if (item == "front") {
      add({Strategy::front});
    } else if (item == "fairing") {
      add({Strategy::fairing});
    } else if (item == "least-area") {
      add({Strategy::liepa, Strategy::least_area});
    } else {
      throw InvalidInput("unknown fallback '" + item +
                         "' (expected fairing, plane, front, least-area or none)");
    }
    start = end + 1;
  }
  if (std::find(chain.begin(), chain.end(), Strategy::plane) != chain.end()) {
    chain.insert(std::find(chain.begin(), chain.end(), Strategy::liepa), Strategy::plane_in_part);
  }
  return chain;
}

namespace {

// Where the fills of `holes` are to be tested against the surface: the box of each loop grown by
// its diameter on every side (a fill that reaches farther is tested against every face).
std::vector<std::array<Vec3, 2>> fill_regions(const Mesh& mesh, const HoleSet& holes) {
  std::vector<std::array<Vec3, 2>> regions;
  for (const BoundaryLoop& loop : holes.loops) {
    Vec3 low = mesh.positions[loop.vertices[0]], high = low;
    for (int v : loop.vertices) {
      low = low.cwiseMin(mesh.positions[v]);
      high = high.cwiseMax(mesh.positions[v]);
    }
    const Vec3 margin = Vec3::Constant((high - low).norm());
    regions.push_back({low - margin, high + margin});
  }
  return regions;
}

}  // namespace

SurfaceContext::SurfaceContext(const Mesh& surface_mesh, double mean_edge_length)
    : mesh(surface_mesh),
      topology(build_topology(surface_mesh)),
      holes(find_holes(surface_mesh, topology)),
      mean_edge(mean_edge_length > 0 ? mean_edge_length
                                     : rangefill::mean_edge_length(surface_mesh, topology)),
      faces(surface_mesh, fill_regions(surface_mesh, holes)) {}

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

// What `fill` gives, a stage's ProcessingError read as a refusal (Refusal::error).
template <typename Work>
FillOutcome refusing_on_error(Work fill) {
  try {
    return fill();
  } catch (const ProcessingError& error) {
    return Refused{Refusal::error, error.what()};
  }
}

// The fill when there is one; else the refusal is recorded for `strategy`.
std::optional<Fill> accepted(FillOutcome outcome, std::optional<Strategy> strategy,
                             HoleReport& report) {
  if (Fill* fill = std::get_if<Fill>(&outcome)) return std::move(*fill);
  report.attempts.push_back({strategy, std::get<Refused>(std::move(outcome))});
  return std::nullopt;
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
                         const Inpainter& inpainter, const FillOptions& options, double height_unit,
                         TrendKind& fitted) {
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
                       const FillOptions& options) {
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

// The fill with larger angles (patch_angles.h), refused unless it joins the mesh as a manifold
// without cutting the surface or itself.
FillOutcome checked(const SurfaceContext& surface, FillOutcome outcome) {
  if (!std::holds_alternative<Fill>(outcome)) return outcome;
  Fill fill = std::get<Fill>(std::move(outcome));
  if (surface.larger_angles)
    fill = with_larger_angles(surface.mesh, surface.topology, std::move(fill));
  if (const auto defect = fill_defect(surface.mesh, surface.topology, fill)) {
    return Refused{Refusal::not_manifold, *defect};
  }
  if (fill_intersects(surface, fill)) return Refused{Refusal::intersects, ""};
  return fill;
}

// Sections VI–VIII on one plane: range image, trend, inpainting, back-projection, stitching.
FillOutcome fill_through_plane(const SurfaceContext& surface, const BoundaryLoop& hole,
                               const Zone& zone, const Frame& frame, const Inpainter& inpainter,
                               const FillOptions& options, HoleReport& report) {
  const Mesh& mesh = surface.mesh;
  const MeshTopology& topology = surface.topology;
  Clock::time_point stage = Clock::now();
  const Zone visible = visible_part(mesh, topology, zone, hole, frame);
  report.zone_faces = static_cast<int>(visible.faces.size());

  RangeImage image = rasterize_zone(mesh, visible, hole, frame, surface.mean_edge, options.image);
  report.gap_pixels = fill_small_gaps(image).pixels;
  report.rim_support = rim_support(image, chords_in_frame(surface, hole, frame));
  if (report.rim_support < options.min_rim_support) {
    return Refused{Refusal::partial_view,
                   "the plane sees only " +
                       std::to_string(static_cast<int>(100 * report.rim_support)) +
                       "% of the hole's surroundings"};
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
  FillOutcome stitched = stitch(mesh, topology, hole, frame, patch, triangulate_grid(patch));
  report.stages.stitching += lap(stage);
  FillOutcome outcome = checked(surface, std::move(stitched));
  report.stages.checking += lap(stage);
  return outcome;
}

// Sections VI–VIII on each plane in turn: the first fill accepted wins, the first refusal is kept;
// no plane at all is a complex hole (VI-C).
FillOutcome fill_through_planes(const SurfaceContext& surface, const BoundaryLoop& hole,
                                const Zone& zone, const std::vector<Projection>& planes,
                                const Inpainter& inpainter, const FillOptions& options,
                                HoleReport& report) {
  std::optional<Refused> first;
  for (const Projection& projection : planes) {
    FillOutcome outcome = refusing_on_error([&] {
      return fill_through_plane(surface, hole, zone, projection.frame, inpainter, options, report);
    });
    if (std::holds_alternative<Fill>(outcome)) return outcome;
    if (!first) first = std::get<Refused>(std::move(outcome));
  }
  if (first) return *first;
  return Refused{Refusal::no_plane, ""};
}

// Section VI-C: the first part of a complex hole that fills, through the planes of that part and
// its own zone.
FillOutcome fill_part_through_planes(const SurfaceContext& surface, const BoundaryLoop& hole,
                                     const Frame& best_frame, const Inpainter& inpainter,
                                     const FillOptions& options, HoleReport& report) {
  std::optional<Refused> first;
  for (const BoundaryLoop& part :
       split_complex_hole(surface.mesh, surface.topology, hole, best_frame)) {
    const Zone zone = grow_zone(surface.mesh, surface.topology, surface.holes, part,
                                surface.mean_edge, options.zone);
    const std::vector<Projection> planes =
        find_projections(surface.mesh, surface.topology, zone, part, options.projection).planes;
    FillOutcome outcome =
        fill_through_planes(surface, part, zone, planes, inpainter, options, report);
    if (std::holds_alternative<Fill>(outcome)) return outcome;
    if (!first) first = std::get<Refused>(std::move(outcome));
  }
  return Refused{Refusal::no_part, first ? refusal_text(first->refusal) : ""};
}

// Tekumalla & Cohen: the advancing front over an MLS surface of the zone's vertices.
FillOutcome fill_through_front(const SurfaceContext& surface, const BoundaryLoop& hole,
                               const Zone& zone, const FillOptions& options) {
  std::vector<Vec3> samples, normals;
  for (int v : zone.vertices) {
    samples.push_back(surface.mesh.positions[v]);
    normals.push_back(vertex_normal(surface.mesh, surface.topology, v));
  }
  return checked(surface,
                 fill_by_front(surface.mesh, surface.topology, surface.faces, hole,
                               MlsSurface(std::move(samples), std::move(normals), options.mls),
                               options.front));
}

// A patch of the hole's own loop without new vertices, as `triangles` of its corners.
FillOutcome loop_patch(const SurfaceContext& surface, const BoundaryLoop& hole,
                       std::vector<Triangle> triangles) {
  if (triangles.empty()) return Refused{Refusal::no_triangulation, ""};
  Fill fill;
  fill.boundary = hole.vertices;
  fill.triangles = std::move(triangles);
  return checked(surface, std::move(fill));
}

std::vector<Vec3> loop_positions(const Mesh& mesh, const BoundaryLoop& hole) {
  std::vector<Vec3> positions;
  for (int v : hole.vertices) positions.push_back(mesh.positions[v]);
  return positions;
}

// The last resort, what MeshLab's Close Holes does: Liepa's weight, whose dihedral angles against
// the faces outside keep the patch from folding into the surface.
FillOutcome fill_by_liepa(const SurfaceContext& surface, const BoundaryLoop& hole) {
  const int n = static_cast<int>(hole.vertices.size());
  std::vector<Vec3> third_points;
  for (int k = 0; k < n; ++k) {
    const int a = hole.vertices[k], b = hole.vertices[(k + 1) % n];
    const int along = find_halfedge(surface.mesh, surface.topology, a, b);
    if (along < 0) throw ProcessingError("hole " + std::to_string(hole.id) + ": not a border loop");
    // The corner of the face outside opposite the edge: where its previous half-edge starts.
    const int third = surface.mesh.triangles[halfedge_face(along)][prev_halfedge(along) % 3];
    third_points.push_back(surface.mesh.positions[third]);
  }
  return loop_patch(surface, hole,
                    triangulate_loop_liepa(loop_positions(surface.mesh, hole), third_points));
}

// The least-area patch of the loop, avoiding the chords the mesh already has.
FillOutcome fill_by_least_area(const SurfaceContext& surface, const BoundaryLoop& hole) {
  std::set<std::pair<int, int>> forbidden;
  for (size_t i = 0; i < hole.vertices.size(); ++i) {
    for (size_t j = i + 2; j < hole.vertices.size(); ++j) {
      const int a = hole.vertices[i], b = hole.vertices[j];
      if (find_halfedge(surface.mesh, surface.topology, a, b) >= 0 ||
          find_halfedge(surface.mesh, surface.topology, b, a) >= 0) {
        forbidden.emplace(static_cast<int>(i), static_cast<int>(j));
      }
    }
  }
  return loop_patch(surface, hole,
                    triangulate_loop_least_area(loop_positions(surface.mesh, hole), forbidden));
}

// The faired patch of the options' continuity, else of a lower one: a higher order continues the
// surroundings' curvature further and may overshoot into the surface where a thin part turns (a
// horn, an ear). The first refusal is the one kept.
FillOutcome fill_by_fairing_descending(const SurfaceContext& surface, const BoundaryLoop& hole,
                                       FairingOptions options) {
  std::optional<Refused> first;
  for (; options.continuity >= 0; --options.continuity) {
    FillOutcome outcome = checked(
        surface, fill_by_fairing(surface.mesh, surface.topology, hole, surface.mean_edge, options));
    if (std::holds_alternative<Fill>(outcome)) return outcome;
    if (!first) first = std::get<Refused>(std::move(outcome));
  }
  return *first;
}

// What one hole's strategies share: its zone, and the planes, searched when first needed.
struct HoleWork {
  const SurfaceContext& surface;
  const BoundaryLoop& hole;
  const Inpainter& inpainter;
  const FillOptions& options;
  HoleReport& report;
  Zone zone;
  std::optional<ProjectionSearch> search;

  const ProjectionSearch& planes() {
    if (!search) {
      Clock::time_point start = Clock::now();
      search = find_projections(surface.mesh, surface.topology, zone, hole, options.projection);
      report.stages.planes += lap(start);
    }
    return *search;
  }

  FillOutcome run(Strategy strategy) {
    switch (strategy) {
      case Strategy::plane:
        return fill_through_planes(surface, hole, zone, planes().planes, inpainter, options,
                                   report);
      case Strategy::front: {
        Clock::time_point start = Clock::now();
        FillOutcome outcome = fill_through_front(surface, hole, zone, options);
        report.stages.front += lap(start);
        return outcome;
      }
      case Strategy::plane_in_part:
        return fill_part_through_planes(surface, hole, planes().best_frame, inpainter, options,
                                        report);
      case Strategy::liepa:
        return fill_by_liepa(surface, hole);
      case Strategy::least_area:
        return fill_by_least_area(surface, hole);
      case Strategy::fairing: {
        // A cap over a fifth of its component (asked for with --fill-all) is no hole to fair:
        // its patch would be as large as the surface, and as slow.
        // So is a hole of more than 3000 d_m² (some 3500 new vertices; the mesh kit's largest are
        // about 1000): the fairing's linear systems grow faster than the image pipeline's.
        const double area_in_dm2 = hole.area / (surface.mean_edge * surface.mean_edge);
        if (is_border(hole) || area_in_dm2 > 3000) return Refused{Refusal::border_sized, ""};
        Clock::time_point start = Clock::now();
        FillOutcome outcome = fill_by_fairing_descending(surface, hole, options.fairing);
        report.stages.fairing += lap(start);
        return outcome;
      }
    }
    return Refused{};
  }
};

// "hole 3: plane: the plane sees only 80% of the hole's surroundings; front: ...".
std::string failure_text(int id, const std::vector<Attempt>& attempts) {
  std::string text = "hole " + std::to_string(id) + ": ";
  for (size_t i = 0; i < attempts.size(); ++i) {
    const Attempt& attempt = attempts[i];
    if (i > 0) text += "; ";
    if (attempt.strategy) text += strategy_name(*attempt.strategy) + ": ";
    text += attempt.refused.detail.empty() ? refusal_text(attempt.refused.refusal)
                                           : attempt.refused.detail;
  }
  return text;
}

}  // namespace

std::optional<Fill> fill_by_chain(const SurfaceContext& surface, const BoundaryLoop& hole,
                                  const Inpainter& inpainter, const FillOptions& options,
                                  bool last_pass, HoleReport& report) {
  const Clock::time_point start = Clock::now();
  Clock::time_point stage = start;
  HoleWork work{surface,
                hole,
                inpainter,
                options,
                report,
                grow_zone(surface.mesh, surface.topology, surface.holes, hole, surface.mean_edge,
                          options.zone),
                std::nullopt};
  report.stages.zone = lap(stage);
  report.rings = work.zone.rings;
  report.zone_faces = static_cast<int>(work.zone.faces.size());
  report.other_holes = work.zone.other_holes;

  std::optional<Fill> fill;
  if (work.zone.faces.empty()) {
    report.attempts.push_back({std::nullopt, {Refusal::empty_zone, ""}});
  }
  for (size_t i = 0; i < options.strategies.size() && !fill && !work.zone.faces.empty(); ++i) {
    const Strategy strategy = options.strategies[i];
    fill = accepted(refusing_on_error([&] { return work.run(strategy); }), strategy, report);
    if (!fill) continue;
    report.strategy = strategy;
    // The rest of a part would stay open after the last pass: a later strategy that fills the
    // whole loop comes first.
    for (size_t j = i + 1;
         j < options.strategies.size() && strategy == Strategy::plane_in_part && last_pass; ++j) {
      const Strategy whole = options.strategies[j];
      if (auto whole_fill =
              accepted(refusing_on_error([&] { return work.run(whole); }), whole, report)) {
        fill = std::move(whole_fill);
        report.strategy = whole;
        break;
      }
    }
  }
  report.seconds = seconds_since(start);
  if (!fill) {
    report.failure = failure_text(hole.id, report.attempts);
    return std::nullopt;
  }
  report.method = strategy_name(*report.strategy);
  report.new_vertices = static_cast<int>(fill->points.size());
  report.new_faces = static_cast<int>(fill->triangles.size());
  report.filled = true;
  return fill;
}

}  // namespace rangefill
