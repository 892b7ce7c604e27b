#include "rangefill/complex_hole.h"

#include <cmath>
#include <optional>

#include "rangefill/geometry2d.h"

namespace rangefill {

namespace {

// A run of a loop: `length` vertices from position `start` on, wrapping round.
struct Run {
  int start = 0;
  int length = 0;
};

std::vector<int> run_vertices(const BoundaryLoop& hole, const Run& run) {
  std::vector<int> vertices;
  const int n = static_cast<int>(hole.vertices.size());
  for (int k = 0; k < run.length; ++k) vertices.push_back(hole.vertices[(run.start + k) % n]);
  return vertices;
}

std::vector<Vec2> run_polygon(const std::vector<Vec2>& projected, const Run& run) {
  std::vector<Vec2> polygon;
  const int n = static_cast<int>(projected.size());
  for (int k = 0; k < run.length; ++k) polygon.push_back(projected[(run.start + k) % n]);
  return polygon;
}

// The first pair of non-adjacent edges (i < j) of the closed polygon that touch.
std::optional<std::pair<int, int>> first_crossing(const std::vector<Vec2>& polygon) {
  const int m = static_cast<int>(polygon.size());
  for (int i = 0; i < m; ++i) {
    for (int j = i + 2; j < m; ++j) {
      if (i == 0 && j == m - 1) continue;
      if (segments_touch(polygon[i], polygon[(i + 1) % m], polygon[j], polygon[(j + 1) % m])) {
        return std::make_pair(i, j);
      }
    }
  }
  return std::nullopt;
}

// Fig. 12: cut the closed run at a crossing of edges i and j. The loop between them, run[i+1..j],
// is again a run; when j is the chord, so is the other side, run[0..i]. Keep the larger by area
// and cut again until the run projects simply.
std::optional<Run> simple_part(const std::vector<Vec2>& projected, Run run) {
  while (run.length >= 3) {
    const std::vector<Vec2> polygon = run_polygon(projected, run);
    const auto crossing = first_crossing(polygon);
    if (!crossing) return run;
    const auto [i, j] = *crossing;
    const int n = static_cast<int>(projected.size());
    std::vector<Run> sides = {{(run.start + i + 1) % n, j - i}};
    if (j == run.length - 1) sides.push_back({run.start, i + 1});
    std::optional<Run> best;
    double best_area = -1;
    for (const Run& side : sides) {
      if (side.length < 3) continue;
      const double area = std::abs(polygon_area(run_polygon(projected, side)));
      if (area > best_area) {
        best = side;
        best_area = area;
      }
    }
    if (!best) return std::nullopt;
    run = *best;
  }
  return std::nullopt;
}

// The longest run of boundary edges whose rim faces face the viewer, as a run of vertices.
std::optional<Run> front_facing_part(const Mesh& mesh, const MeshTopology& topology,
                                     const BoundaryLoop& hole, const Vec3& view) {
  const int n = static_cast<int>(hole.vertices.size());
  std::vector<char> front(n);
  for (int k = 0; k < n; ++k) {
    const int h = find_halfedge(mesh, topology, hole.vertices[k], hole.vertices[(k + 1) % n]);
    front[k] = h >= 0 && triangle_cross(mesh, halfedge_face(h)).dot(view) > 0;
  }
  int first_back = 0;
  while (first_back < n && front[first_back]) ++first_back;
  if (first_back == n) return std::nullopt;  // the whole rim faces the viewer
  Run best;
  for (int k = 1, length = 0; k <= n; ++k) {  // scan once round, starting after a back edge
    const int edge = (first_back + k) % n;
    if (front[edge] && k < n) {
      ++length;
      continue;
    }
    if (length > best.length - 1) best = {(edge - length + n) % n, length + 1};
    length = 0;
  }
  if (best.length < 3) return std::nullopt;
  return best;
}

}  // namespace

BoundaryLoop make_loop(const Mesh& mesh, int id, std::vector<int> vertices) {
  BoundaryLoop loop;
  loop.id = id;
  Vec3 vector_area = Vec3::Zero();
  for (size_t k = 0; k < vertices.size(); ++k) {
    const Vec3& p = mesh.positions[vertices[k]];
    const Vec3& q = mesh.positions[vertices[(k + 1) % vertices.size()]];
    loop.perimeter += (q - p).norm();
    vector_area += p.cross(q);
  }
  loop.area = 0.5 * vector_area.norm();
  loop.vertices = std::move(vertices);
  return loop;
}

std::vector<BoundaryLoop> split_complex_hole(const Mesh& mesh, const MeshTopology& topology,
                                             const BoundaryLoop& hole, const Frame& frame) {
  const std::vector<Vec2> projected = project_loop(mesh, hole, frame);
  const int n = static_cast<int>(projected.size());
  std::vector<Run> candidates;
  if (const auto part = simple_part(projected, {0, n})) candidates.push_back(*part);
  if (const auto part = front_facing_part(mesh, topology, hole, frame.normal())) {
    if (const auto simple = simple_part(projected, *part)) candidates.push_back(*simple);
  }
  std::vector<BoundaryLoop> parts;
  for (const Run& run : candidates) {
    if (run.length < 3 || run.length >= n) continue;
    std::vector<int> vertices = run_vertices(hole, run);
    const int first = vertices.front(), last = vertices.back();
    if (find_halfedge(mesh, topology, first, last) >= 0 ||
        find_halfedge(mesh, topology, last, first) >= 0) {
      continue;  // the chord would double an existing edge
    }
    parts.push_back(make_loop(mesh, hole.id, std::move(vertices)));
  }
  return parts;
}

}  // namespace rangefill
