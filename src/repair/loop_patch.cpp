// The core's one translation unit with CGAL's hole triangulation (heavy headers).
#include "rangefill/repair/loop_patch.h"

#include <algorithm>
#include <iterator>
#include <limits>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include "rangefill/core/errors.h"

namespace rangefill {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
namespace pmp = CGAL::Polygon_mesh_processing;

}  // namespace

std::vector<Triangle> triangulate_loop_liepa(const std::vector<Vec3>& loop,
                                             const std::vector<Vec3>& third_points) {
  if (third_points.size() != loop.size()) {
    throw InvalidInput("triangulate_loop_liepa: " + std::to_string(third_points.size()) +
                       " third points for a loop of " + std::to_string(loop.size()) + " edges");
  }
  auto points_of = [](const std::vector<Vec3>& positions) {
    std::vector<Kernel::Point_3> points;
    for (const Vec3& p : positions) points.emplace_back(p.x(), p.y(), p.z());
    return points;
  };
  std::vector<CGAL::Triple<int, int, int>> patch;
  // Over every triangle of the loop's vertices, not only those of their 3D Delaunay
  // triangulation: the order in which CGAL's triangulation visits them depends on where the heap
  // puts its cells, and so did the patch.
  pmp::triangulate_hole_polyline(
      points_of(loop), points_of(third_points), std::back_inserter(patch),
      CGAL::parameters::use_2d_constrained_delaunay_triangulation(false).use_delaunay_triangulation(
          false));
  std::vector<Triangle> triangles;
  bool along_loop = false;  // whether the patch uses the edge 0 → 1 as the loop runs
  for (const auto& t : patch) {
    const Triangle triangle = {t.first, t.second, t.third};
    for (int k = 0; k < 3; ++k) along_loop |= triangle[k] == 0 && triangle[(k + 1) % 3] == 1;
    triangles.push_back(triangle);
  }
  if (along_loop) {
    for (Triangle& t : triangles) std::swap(t[1], t[2]);
  }
  return triangles;
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
