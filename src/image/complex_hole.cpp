#include "rangefill/image/complex_hole.h"

#include <cmath>
#include <functional>
#include <limits>
#include <optional>

#include "rangefill/core/geometry2d.h"

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

// Whether the chord from the vertex at loop position i to the one at j can close a part: it is no
// edge of the mesh, and at both ends it leaves into the hole, not over the surface. The surface
// lies left of the loop (holes.h): at a vertex, the hole lies right of the incoming and of the
// outgoing boundary edge, each in the plane of its face; both when the loop turns right there (a
// convex corner of the hole), either when it turns left (a reflex one).
bool valid_chord(const Mesh& mesh, const MeshTopology& topology, const BoundaryLoop& hole, int i,
                 int j) {
  const int n = static_cast<int>(hole.vertices.size());
  const int a = hole.vertices[i], b = hole.vertices[j];
  if (has_edge(mesh, topology, a, b)) {
    return false;
  }
  // The direction right of the boundary edge from -> to, in the plane of its face.
  auto right_of = [&](int from, int to) -> std::optional<Vec3> {
    const int h = find_halfedge(mesh, topology, from, to);
    if (h < 0) return std::nullopt;
    return Vec3(
        (mesh.positions[to] - mesh.positions[from]).cross(triangle_cross(mesh, halfedge_face(h))));
  };
  auto enters_hole = [&](int at, int towards) {
    const int v = hole.vertices[at], previous = hole.vertices[(at + n - 1) % n],
              next = hole.vertices[(at + 1) % n];
    const auto right_in = right_of(previous, v), right_out = right_of(v, next);
    if (!right_in || !right_out) return false;
    const Vec3 chord = mesh.positions[hole.vertices[towards]] - mesh.positions[v];
    const bool in = chord.dot(*right_in) > 0, out = chord.dot(*right_out) > 0;
    const bool turns_right = (mesh.positions[next] - mesh.positions[v]).dot(*right_in) > 0;
    return turns_right ? in && out : in || out;
  };
  return enters_hole(i, j) && enters_hole(j, i);
}

// Where a closed run is narrowest: the chord between run positions a < b, with at least one
// vertex between them either way round, of least 3-D length relative to the shorter of the two
// arcs of the run's polygon (its closing chord included) that it separates, among the chords
// `allowed` takes. A long thin hole, or one wrapping round a limb, is cut across, not along.
std::optional<std::pair<int, int>> narrowest_neck(const std::vector<Vec3>& points,
                                                  const std::function<bool(int, int)>& allowed) {
  const int m = static_cast<int>(points.size());
  std::vector<double> arc(m + 1, 0);  // arc[k]: length of the polygon from point 0 to point k
  for (int k = 0; k < m; ++k) arc[k + 1] = arc[k] + (points[(k + 1) % m] - points[k]).norm();
  std::optional<std::pair<int, int>> best;
  double best_ratio = std::numeric_limits<double>::infinity();
  for (int a = 0; a < m; ++a) {
    for (int b = a + 2; b < m && b - a <= m - 2; ++b) {
      const double shorter = std::min(arc[b] - arc[a], arc[m] - (arc[b] - arc[a]));
      const double ratio = (points[b] - points[a]).norm() / shorter;
      if (ratio < best_ratio && allowed(a, b)) {
        best_ratio = ratio;
        best = std::make_pair(a, b);
      }
    }
  }
  return best;
}

// Parts cut off at necks (narrowest_neck): both sides of the hole's narrowest neck, larger first,
// then, `depth` − 1 times more, the side of each part's own narrowest neck that is a run of the
// hole.
std::vector<Run> neck_parts(const Mesh& mesh, const MeshTopology& topology,
                            const BoundaryLoop& hole, int depth) {
  const int n = static_cast<int>(hole.vertices.size());
  auto neck_of = [&](const Run& run) -> std::optional<std::pair<int, int>> {
    std::vector<Vec3> points;
    for (int v : run_vertices(hole, run)) points.push_back(mesh.positions[v]);
    return narrowest_neck(points, [&](int a, int b) {
      return valid_chord(mesh, topology, hole, (run.start + a) % n, (run.start + b) % n);
    });
  };
  std::vector<Run> parts, level;
  if (const auto neck = neck_of({0, n})) {
    const auto [a, b] = *neck;
    level = {{a, b - a + 1}, {b, n - (b - a) + 1}};
    if (level[1].length > level[0].length) std::swap(level[0], level[1]);
  }
  for (int round = 1; round < depth && !level.empty(); ++round) {
    std::vector<Run> inner;
    for (const Run& run : level) {
      if (const auto neck = neck_of(run))
        inner.push_back({(run.start + neck->first) % n, neck->second - neck->first + 1});
    }
    parts.insert(parts.end(), level.begin(), level.end());
    level = std::move(inner);
  }
  parts.insert(parts.end(), level.begin(), level.end());
  return parts;
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
                                             const BoundaryLoop& hole, const HoleInPlane& plane) {
  const Frame& frame = plane.frame;
  const std::vector<Vec2>& projected = plane.loop;
  const int n = static_cast<int>(projected.size());
  std::vector<Run> candidates;
  if (const auto part = simple_part(projected, {0, n})) candidates.push_back(*part);
  if (const auto part = front_facing_part(mesh, topology, hole, frame.normal())) {
    if (const auto simple = simple_part(projected, *part)) candidates.push_back(*simple);
  }
  for (const Run& part : neck_parts(mesh, topology, hole, 3)) candidates.push_back(part);
  std::vector<BoundaryLoop> parts;
  for (const Run& run : candidates) {
    if (run.length < 3 || run.length >= n) continue;
    if (!valid_chord(mesh, topology, hole, (run.start + run.length - 1) % n, run.start)) continue;
    parts.push_back(make_loop(mesh, hole.id, run_vertices(hole, run)));
  }
  return parts;
}

}  // namespace rangefill
