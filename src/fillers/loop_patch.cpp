// The core's one translation unit with CGAL's 3D Delaunay triangulation (heavy headers).
#include "rangefill/fillers/loop_patch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <unordered_map>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "rangefill/core/errors.h"

namespace rangefill {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

// Liepa's weight of a patch (as CGAL's Weight_min_max_dihedral_and_area): its largest dihedral
// angle (degrees between the normals), then its area.
struct LiepaWeight {
  double angle = 0, area = 0;
  LiepaWeight operator+(const LiepaWeight& other) const {
    return {std::max(angle, other.angle), area + other.area};
  }
  bool operator<(const LiepaWeight& other) const {
    return angle != other.angle ? angle < other.angle : area < other.area;
  }
};

// The best patch found for the sub-polygon i..k: its weight and the third corner of its triangle
// on (i, k); none for a sub-polygon without a patch.
struct SubPatch {
  LiepaWeight weight;
  int third = -1;
};

// Liepa's dynamic programme over the sub-polygons i..k (i < k) of a loop of n points P with
// the third points Q of the faces outside. Sub-polygons are solved from the shortest, each over
// its allowed third corners in increasing order, the first of equal weights kept: the same
// patch whatever order a search space was built in.
class LiepaSearch {
 public:
  LiepaSearch(const std::vector<Point>& points, const std::vector<Point>& third_points,
              const std::set<std::pair<int, int>>& forbidden)
      : P(points), Q(third_points), forbidden_(forbidden), n(static_cast<int>(points.size())) {}

  // The triangles of the least-weight patch whose triangles (i, j, k) all have j among
  // `thirds(i, k)` (increasing); empty when there is none.
  template <class Thirds>
  std::vector<Triangle> search(const std::vector<std::pair<int, int>>& ranges, Thirds thirds) {
    solved_.clear();
    for (const auto& [i, k] : ranges) {
      std::optional<SubPatch> best;
      for (int j : thirds(i, k)) {
        if (!allowed(i, j, k)) continue;
        const SubPatch* left = sub_patch(i, j);
        const SubPatch* right = sub_patch(j, k);
        if (!left || !right) continue;
        const LiepaWeight weight = left->weight + right->weight + triangle_weight(i, j, k);
        if (!best || weight < best->weight) best = SubPatch{weight, j};
      }
      if (best) solved_[key(i, k)] = *best;
    }
    std::vector<Triangle> triangles;
    if (!sub_patch(0, n - 1)) return triangles;
    std::vector<std::pair<int, int>> stack = {{0, n - 1}};
    while (!stack.empty()) {
      const auto [i, k] = stack.back();
      stack.pop_back();
      if (k - i < 2) continue;
      const int j = solved_.at(key(i, k)).third;
      triangles.push_back({k, j, i});  // holds j → i and k → j: the loop's edges reversed
      stack.emplace_back(i, j);
      stack.emplace_back(j, k);
    }
    return triangles;
  }

 private:
  int64_t key(int i, int k) const { return static_cast<int64_t>(i) * n + k; }

  const SubPatch* sub_patch(int i, int k) const {
    static const SubPatch edge;
    if (k == i + 1) return &edge;
    const auto found = solved_.find(key(i, k));
    return found == solved_.end() ? nullptr : &found->second;
  }

  bool is_loop_edge(int a, int b) const { return b == a + 1 || (a == 0 && b == n - 1); }

  // Not degenerate, and no chord the mesh already has.
  bool allowed(int i, int j, int k) const {
    for (const auto& [a, b] : {std::pair(i, j), std::pair(j, k), std::pair(i, k)}) {
      if (!is_loop_edge(a, b) && forbidden_.count({a, b})) return false;
    }
    return !CGAL::collinear(P[i], P[j], P[k]);
  }

  // 180° less the dihedral angle at edge (a, b) between triangles (a, b, c) and (a, b, d).
  double normal_angle(int a, int b, int c, const Point& d) const {
    return 180 - std::abs(CGAL::approximate_dihedral_angle(P[a], P[b], P[c], d));
  }

  // Triangle (i, j, k): its angles with the faces outside across loop edges and with the
  // triangles of the sub-patches on (i, j) and (j, k); the triangle on (i, k) is not known yet.
  LiepaWeight triangle_weight(int i, int j, int k) const {
    double angle = 0;
    const std::array<std::array<int, 3>, 3> edges = {{{i, j, k}, {j, k, i}, {k, i, j}}};
    for (int e = 0; e < 3; ++e) {
      const auto [a, b, c] = edges[e];
      if (b == a + 1) {
        angle = std::max(angle, normal_angle(a, b, c, Q[a]));
      } else if (e == 2 && a == n - 1 && b == 0) {
        angle = std::max(angle, normal_angle(a, b, c, Q[n - 1]));
      } else if (e < 2) {
        angle = std::max(angle, normal_angle(a, b, c, P[solved_.at(key(a, b)).third]));
      }
    }
    return {angle, std::sqrt(CGAL::to_double(CGAL::squared_area(P[i], P[j], P[k])))};
  }

  const std::vector<Point>& P;
  const std::vector<Point>& Q;
  const std::set<std::pair<int, int>>& forbidden_;
  const int n;
  std::unordered_map<int64_t, SubPatch> solved_;
};

// The triangles (i < j < k) of the 3D Delaunay triangulation of `points`, and every triangle
// on a loop edge it lacks (CGAL's search space for Liepa's weight); empty when the points span
// no plane.
std::set<std::array<int, 3>> delaunay_search_space(const std::vector<Point>& points) {
  using Vertex = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
  using Structure =
      CGAL::Triangulation_data_structure_3<Vertex,
                                           CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;
  using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Structure>;
  const int n = static_cast<int>(points.size());
  std::vector<std::pair<Point, int>> indexed;
  for (int i = 0; i < n; ++i) indexed.emplace_back(points[i], i);
  const Delaunay delaunay(indexed.begin(), indexed.end());
  std::set<std::array<int, 3>> triangles;
  if (delaunay.dimension() < 2) return triangles;
  std::set<std::pair<int, int>> edges;
  for (auto facet = delaunay.finite_facets_begin(); facet != delaunay.finite_facets_end();
       ++facet) {
    std::array<int, 3> corners;
    for (int c = 0, m = 0; c < 4; ++c) {
      if (c != facet->second) corners[m++] = facet->first->vertex(c)->info();
    }
    std::sort(corners.begin(), corners.end());
    triangles.insert(corners);
    edges.insert({corners[0], corners[1]});
    edges.insert({corners[1], corners[2]});
    edges.insert({corners[0], corners[2]});
  }
  for (int a = 0; a < n; ++a) {
    const std::pair<int, int> edge = a + 1 < n ? std::pair(a, a + 1) : std::pair(0, n - 1);
    if (edges.count(edge)) continue;
    for (int c = 0; c < n; ++c) {
      if (c == edge.first || c == edge.second) continue;
      std::array<int, 3> corners = {edge.first, edge.second, c};
      std::sort(corners.begin(), corners.end());
      triangles.insert(corners);
    }
  }
  return triangles;
}

}  // namespace

std::vector<Triangle> triangulate_loop_liepa(const std::vector<Vec3>& loop,
                                             const std::vector<Vec3>& third_points,
                                             const std::set<std::pair<int, int>>& forbidden) {
  if (third_points.size() != loop.size()) {
    throw InvalidInput("triangulate_loop_liepa: " + std::to_string(third_points.size()) +
                       " third points for a loop of " + std::to_string(loop.size()) + " edges");
  }
  const int n = static_cast<int>(loop.size());
  if (n < 3) return {};
  auto points_of = [](const std::vector<Vec3>& positions) {
    std::vector<Point> points;
    for (const Vec3& p : positions) points.emplace_back(p.x(), p.y(), p.z());
    return points;
  };
  const std::vector<Point> P = points_of(loop), Q = points_of(third_points);
  LiepaSearch search(P, Q, forbidden);

  // Among the Delaunay triangles first: the sub-polygons on their edges, shortest first.
  const std::set<std::array<int, 3>> space = delaunay_search_space(P);
  std::map<std::pair<int, int>, std::vector<int>> thirds;  // increasing, as `space` is sorted
  for (const auto& [i, j, k] : space) thirds[{i, k}].push_back(j);
  std::vector<std::pair<int, int>> ranges;
  for (const auto& entry : thirds) ranges.push_back(entry.first);
  const auto shorter = [](const std::pair<int, int>& a, const std::pair<int, int>& b) {
    return std::make_pair(a.second - a.first, a) < std::make_pair(b.second - b.first, b);
  };
  std::sort(ranges.begin(), ranges.end(), shorter);
  std::vector<Triangle> triangles =
      search.search(ranges, [&](int i, int k) -> const std::vector<int>& {
        return thirds.at({i, k});
      });
  if (!triangles.empty()) return triangles;

  // Failing that, among all triangles of the loop's points.
  ranges.clear();
  for (int length = 2; length < n; ++length) {
    for (int i = 0; i + length < n; ++i) ranges.emplace_back(i, i + length);
  }
  return search.search(ranges, [](int i, int k) {
    std::vector<int> all(k - i - 1);
    std::iota(all.begin(), all.end(), i + 1);
    return all;
  });
}

std::vector<Triangle> triangulate_loop_least_area(const std::vector<Vec3>& loop,
                                                  const std::set<std::pair<int, int>>& forbidden) {
  const int n = static_cast<int>(loop.size());
  if (n < 3) return {};
  if (n == 3) return {{2, 1, 0}};
  // Minimal-area triangulation by dynamic programming over the polygon (Barequet–Sharir; the
  // area weight of Liepa 2003): area[i][j] is the least area closing the sub-polygon i..j.
  const double infinity = std::numeric_limits<double>::infinity();
  std::vector<double> area(static_cast<size_t>(n) * n, infinity);
  std::vector<int> split(static_cast<size_t>(n) * n, -1);
  auto at = [n](int i, int j) { return static_cast<size_t>(i) * n + j; };
  auto allowed = [&](int i, int j) {
    return j == i + 1 || (i == 0 && j == n - 1) ||
           !forbidden.count({std::min(i, j), std::max(i, j)});
  };
  for (int i = 0; i + 1 < n; ++i) area[at(i, i + 1)] = 0;
  for (int length = 2; length < n; ++length) {
    for (int i = 0; i + length < n; ++i) {
      const int j = i + length;
      if (!allowed(i, j)) continue;
      for (int k = i + 1; k < j; ++k) {
        const double candidate = area[at(i, k)] + area[at(k, j)] +
                                 0.5 * (loop[k] - loop[i]).cross(loop[j] - loop[i]).norm();
        if (candidate < area[at(i, j)]) {
          area[at(i, j)] = candidate;
          split[at(i, j)] = k;
        }
      }
    }
  }
  if (!(area[at(0, n - 1)] < infinity)) return {};
  std::vector<Triangle> triangles;
  std::vector<std::pair<int, int>> stack = {{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) continue;
    const int k = split[at(i, j)];
    triangles.push_back({j, k, i});  // holds k → i and j → k: the loop's edges reversed
    stack.emplace_back(i, k);
    stack.emplace_back(k, j);
  }
  return triangles;
}

}  // namespace rangefill
