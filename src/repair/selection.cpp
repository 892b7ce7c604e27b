#include "rangefill/repair/selection.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <set>

#include "core/cgal_triangles.h"
#include "rangefill/core/errors.h"
#include "rangefill/hole/zone.h"

namespace rangefill {

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

namespace {

// Rings of the faces kept around the band: what the fillers read around the enlarged hole (the
// zone of eq. 2 for its area, their own context rings), and one more.
int context_rings(const SurfaceContext& surface, const BoundaryLoop& hole, int band_rings,
                  const FillerChain& fillers, const ZoneOptions& zone) {
  const double band_width = band_rings * surface.mean_edge;
  const double enlarged_area =
      hole.area + hole.perimeter * band_width + M_PI * band_width * band_width;
  int rings = zone.rings > 0 ? zone.rings : rings_for_hole(enlarged_area, surface.mean_edge, zone);
  for (const auto& filler : fillers) rings = std::max(rings, filler->context_rings());
  return rings + 1;
}

}  // namespace

std::optional<Fill> fill_by_selection(const SurfaceContext& surface, const BoundaryLoop& hole,
                                      const SelectionOptions& selection, const FillerChain& chain,
                                      const ChainOptions& options, HoleReport& report) {
  const FillerChain& candidates = selection.candidates;
  std::optional<BandTest> test;
  if (!candidates.empty()) {
    FillerChain read = candidates;
    read.insert(read.end(), chain.begin(), chain.end());
    test = hide_band(surface, hole, selection.band_rings,
                     context_rings(surface, hole, selection.band_rings, read, options.zone));
  }
  if (!test) return fill_by_chain(surface, hole, chain, options, report);

  const SurfaceContext band_surface(test->mesh, surface.mean_edge);
  ChainOptions on_band = options;
  on_band.on_images = nullptr;  // the images are of the hole itself
  on_band.last_pass = false;
  on_band.acceptance.larger_angles = false;  // a fill's shape, not its triangles' angles, is scored
  std::vector<size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), 0);
  for (const auto& candidate : candidates) {
    const auto start = std::chrono::steady_clock::now();
    HoleReport scratch;
    scratch.id = report.id;
    const std::optional<Fill> fill =
        fill_by_chain(band_surface, test->hole, {candidate}, on_band, scratch);
    CandidateScore score{candidate->name(), std::nullopt, 0};
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
    HoleReport tried = report;
    tried.attempts = attempts;
    std::optional<Fill> fill = fill_by_chain(surface, hole, {candidates[i]}, options, tried);
    attempts = tried.attempts;
    if (fill) {
      report = std::move(tried);
      report.selected = candidates[i]->name();
      return fill;
    }
  }
  HoleReport chained = report;
  chained.attempts = attempts;
  std::optional<Fill> fill = fill_by_chain(surface, hole, chain, options, chained);
  report = std::move(chained);
  return fill;
}

}  // namespace rangefill
