#include "rangefill/repair/selection.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <set>

#include "core/cgal_triangles.h"
#include "rangefill/core/errors.h"
#include "rangefill/repair/zone.h"

namespace rangefill {

namespace {

Candidate candidate_from_name(const std::string& name) {
  Candidate candidate;
  candidate.name = name;
  const size_t colon = name.find(':');
  const std::string filler = name.substr(0, colon);
  const std::string variant = colon == std::string::npos ? "" : name.substr(colon + 1);
  if (filler == "fairing") {
    candidate.strategy = Strategy::fairing;
    if (variant == "c0" || variant == "c1" || variant == "c2") {
      candidate.continuity = variant[1] - '0';
    } else if (!variant.empty()) {
      throw InvalidInput("unknown candidate '" + name + "' (fairing takes :c0, :c1 or :c2)");
    }
  } else if (filler == "plane") {
    candidate.strategy = Strategy::plane;
    candidate.inpainter = variant;
  } else if (filler == "front" && variant.empty()) {
    candidate.strategy = Strategy::front;
  } else {
    throw InvalidInput("unknown candidate '" + name +
                       "' (expected fairing[:c0|:c1|:c2], plane[:BACKEND] or front)");
  }
  return candidate;
}

}  // namespace

std::vector<Candidate> parse_candidates(const std::string& list) {
  std::vector<Candidate> candidates;
  if (list.empty() || list == "none") return candidates;
  for (size_t start = 0; start <= list.size();) {
    const size_t end = std::min(list.find(',', start), list.size());
    Candidate candidate = candidate_from_name(list.substr(start, end - start));
    for (const Candidate& other : candidates) {
      if (other.name == candidate.name) {
        throw InvalidInput("candidate '" + candidate.name + "' listed twice");
      }
    }
    candidates.push_back(std::move(candidate));
    start = end + 1;
  }
  return candidates;
}

std::optional<BandTest> hide_band(const SurfaceContext& surface, const BoundaryLoop& hole,
                                  int band_rings, int context_rings) {
  if (band_rings < 1 || context_rings < 1) {
    throw InvalidInput("band test: band and context rings must be at least 1");
  }
  const Mesh& mesh = surface.mesh;
  const std::vector<int> band =
      faces_within_rings(mesh, surface.topology, hole.vertices, band_rings);
  const std::vector<int> region =
      faces_within_rings(mesh, surface.topology, hole.vertices, band_rings + context_rings);
  std::vector<int> kept;
  std::set_difference(region.begin(), region.end(), band.begin(), band.end(),
                      std::back_inserter(kept));
  if (kept.empty()) return std::nullopt;

  BandTest test;
  std::vector<int> used;
  for (int face : kept)
    used.insert(used.end(), mesh.triangles[face].begin(), mesh.triangles[face].end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  for (int v : used) add_vertex(test.mesh, mesh.positions[v], kOriginal);
  // A kept vertex's number in test.mesh is its place in `used` (ascending); -1 if not kept.
  const auto local = [&](int v) {
    const auto found = std::lower_bound(used.begin(), used.end(), v);
    return found != used.end() && *found == v ? static_cast<int>(found - used.begin()) : -1;
  };
  for (int face : kept) {
    const Triangle& t = mesh.triangles[face];
    add_face(test.mesh, {local(t[0]), local(t[1]), local(t[2])}, kOriginal);
  }
  std::set<int> band_vertices;
  for (int face : band)
    band_vertices.insert(mesh.triangles[face].begin(), mesh.triangles[face].end());
  for (int v : band_vertices) {
    if (local(v) < 0) test.hidden.push_back(mesh.positions[v]);
  }
  if (test.hidden.empty()) return std::nullopt;

  // The enlarged hole: the one loop through the band's kept vertices, none of whose vertices is
  // on another loop of the surface.
  std::set<int> other_loops;
  for (const BoundaryLoop& loop : surface.holes.loops) {
    if (loop.id != hole.id) other_loops.insert(loop.vertices.begin(), loop.vertices.end());
  }
  const MeshTopology topology = build_topology(test.mesh);
  const HoleSet holes = find_holes(test.mesh, topology);
  if (!holes.pinched_vertices.empty() || holes.open_boundary_edges > 0) return std::nullopt;
  const BoundaryLoop* enlarged = nullptr;
  for (const BoundaryLoop& loop : holes.loops) {
    const bool touches_band = std::any_of(loop.vertices.begin(), loop.vertices.end(),
                                          [&](int v) { return band_vertices.count(used[v]) > 0; });
    if (!touches_band) continue;
    if (enlarged) return std::nullopt;  // the band cut the surface into several loops
    enlarged = &loop;
  }
  if (!enlarged) return std::nullopt;
  for (int v : enlarged->vertices) {
    if (other_loops.count(used[v])) return std::nullopt;
  }
  test.hole = *enlarged;
  const double component_area = surface.holes.component_areas[hole.component];
  test.hole.area_share = component_area > 0 ? test.hole.area / component_area : 0;
  return test;
}

double band_distance(const BandTest& test, const Fill& fill) {
  using namespace cgal_triangles;
  const int boundary_size = static_cast<int>(fill.boundary.size());
  const auto position = [&](int v) -> const Vec3& {
    return v < boundary_size ? test.mesh.positions[fill.boundary[v]]
                             : fill.points[v - boundary_size];
  };
  std::vector<CgalTriangle> triangles;
  for (const Triangle& t : fill.triangles) {
    triangles.emplace_back(to_point(position(t[0])), to_point(position(t[1])),
                           to_point(position(t[2])));
  }
  if (triangles.empty()) throw InvalidInput("band distance: the fill has no triangle");
  AabbTree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  double sum = 0;
  for (const Vec3& p : test.hidden) sum += tree.squared_distance(to_point(p));
  return std::sqrt(sum / static_cast<double>(test.hidden.size()));
}

CandidateFillers::CandidateFillers(const std::vector<Candidate>& list,
                                   const std::string& default_inpainter,
                                   const InpainterOptions& inpainting)
    : candidates(list) {
  for (const Candidate& candidate : candidates) {
    inpainters.push_back(
        candidate.strategy == Strategy::plane
            ? make_inpainter(candidate.inpainter.empty() ? default_inpainter : candidate.inpainter,
                             inpainting)
            : nullptr);
  }
}

namespace {

// The options of `options` that run `candidate` alone.
FillOptions candidate_options(const FillOptions& options, const Candidate& candidate) {
  FillOptions alone = options;
  alone.strategies = {candidate.strategy};
  alone.fairing.continuity = candidate.continuity;
  return alone;
}

// Rings of the faces kept around the band: what the candidates read around the enlarged hole
// (the zone of eq. 2 for its area, the fairing's rings), and one more.
int context_rings(const SurfaceContext& surface, const BoundaryLoop& hole, int band_rings,
                  const FillOptions& options) {
  const double band_width = band_rings * surface.mean_edge;
  const double enlarged_area =
      hole.area + hole.perimeter * band_width + M_PI * band_width * band_width;
  const int zone_rings = options.zone.rings > 0
                             ? options.zone.rings
                             : rings_for_hole(enlarged_area, surface.mean_edge, options.zone);
  return std::max(zone_rings, options.fairing.rings) + 1;
}

}  // namespace

std::optional<Fill> fill_by_selection(const SurfaceContext& surface, const BoundaryLoop& hole,
                                      const CandidateFillers& fillers, int band_rings,
                                      const Inpainter& inpainter, const FillOptions& options,
                                      bool last_pass, HoleReport& report) {
  std::optional<BandTest> test;
  if (!fillers.candidates.empty()) {
    test = hide_band(surface, hole, band_rings, context_rings(surface, hole, band_rings, options));
  }
  if (!test) return fill_by_chain(surface, hole, inpainter, options, last_pass, report);

  SurfaceContext band_surface(test->mesh, surface.mean_edge);
  band_surface.larger_angles = false;  // a fill's shape, not its triangles' angles, is scored
  std::vector<size_t> order(fillers.candidates.size());
  std::iota(order.begin(), order.end(), 0);
  for (size_t i = 0; i < fillers.candidates.size(); ++i) {
    const Candidate& candidate = fillers.candidates[i];
    const Inpainter& candidate_inpainter = fillers.inpainter_of(i, inpainter);
    const auto start = std::chrono::steady_clock::now();
    HoleReport scratch;
    FillOptions on_band = candidate_options(options, candidate);
    on_band.on_images = nullptr;  // the images are of the hole itself
    const std::optional<Fill> fill =
        fill_by_chain(band_surface, test->hole, candidate_inpainter, on_band, false, scratch);
    CandidateScore score{candidate.name, std::nullopt, 0};
    if (fill) score.score = band_distance(*test, *fill) / surface.mean_edge;
    score.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report.selection.push_back(score);
  }
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const auto& sa = report.selection[a].score;
    const auto& sb = report.selection[b].score;
    return sa && (!sb || *sa < *sb);
  });
  std::vector<Attempt> attempts;
  for (size_t i : order) {
    const Candidate& candidate = fillers.candidates[i];
    HoleReport tried = report;
    tried.attempts = attempts;
    std::optional<Fill> fill =
        fill_by_chain(surface, hole, fillers.inpainter_of(i, inpainter),
                      candidate_options(options, candidate), last_pass, tried);
    attempts = tried.attempts;
    if (fill) {
      report = std::move(tried);
      report.selected = candidate.name;
      return fill;
    }
  }
  HoleReport chained = report;
  chained.attempts = attempts;
  std::optional<Fill> fill = fill_by_chain(surface, hole, inpainter, options, last_pass, chained);
  report = std::move(chained);
  return fill;
}

}  // namespace rangefill
