// The zone of interest (zone.h): eq. 2 for the number of rings, ring growth on a grid, the normal
// diffusion test of eq. 4 across a fold, and the other holes a zone reaches.
#include "rangefill/hole/zone.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "support.h"

namespace rangefill {
namespace {

using testing::make_grid;
using testing::remove_faces;

// Vertex id of grid point (x, y) in make_grid(n).
int grid_id(int n, int x, int y) {
  return y * (n + 1) + x;
}

// make_grid(n) without the faces inside the axis-aligned rectangle [x0, x1] × [y0, y1].
Mesh grid_with_holes(int n, const std::vector<std::array<double, 4>>& rectangles) {
  return remove_faces(make_grid(n), [&](const Vec3& p) {
    return std::any_of(rectangles.begin(), rectangles.end(), [&](const std::array<double, 4>& r) {
      return p.x() >= r[0] && p.x() <= r[2] && p.y() >= r[1] && p.y() <= r[3];
    });
  });
}

// The loop of `holes` that passes through `vertex`; fails the test if none does.
const BoundaryLoop& loop_through(const HoleSet& holes, int vertex) {
  for (const BoundaryLoop& loop : holes.loops) {
    if (std::count(loop.vertices.begin(), loop.vertices.end(), vertex)) return loop;
  }
  ADD_FAILURE() << "no loop passes through vertex " << vertex;
  return holes.loops.front();
}

Zone zone_of(const Mesh& mesh, const BoundaryLoop& hole, const ZoneOptions& options) {
  const MeshTopology topology = build_topology(mesh);
  const HoleSet holes = find_holes(mesh, topology);
  return grow_zone(mesh, topology, holes, hole, mean_edge_length(mesh, topology), options);
}

// Eq. 2 in units of d_m: ν = A' / (0.106 κ A' + 18) with A' = A / d_m², rounded to the nearest.
TEST(RingsForHole, MatchesEquationTwoInUnitsOfMeanEdge) {
  const ZoneOptions options;  // κ = 0.15, rings clamped to [3, 40]
  // A' = 1800: 1800 / (0.0159 · 1800 + 18) = 1800 / 46.62 = 38.61 → 39.
  EXPECT_EQ(rings_for_hole(1800, 1, options), 39);
  // A' = 360: 360 / (5.724 + 18) = 15.17 → 15.
  EXPECT_EQ(rings_for_hole(360, 1, options), 15);
  // A' = 100: 100 / 19.59 = 5.10 → 5; the same hole at another scale gives the same ν.
  EXPECT_EQ(rings_for_hole(100, 1, options), 5);
  EXPECT_EQ(rings_for_hole(400, 2, options), 5);
  EXPECT_EQ(rings_for_hole(1e-4, 1e-3, options), 5);
  // κ enters the denominator: κ = 0.5 → 1800 / (0.053 · 1800 + 18) = 1800 / 113.4 = 15.87 → 16.
  ZoneOptions kappa = options;
  kappa.kappa = 0.5;
  EXPECT_EQ(rings_for_hole(1800, 1, kappa), 16);
}

// ν is clamped to [min_rings, max_rings]: tiny holes get min_rings, huge ones (ν tends to
// 1 / (0.106 κ) ≈ 62.9) get max_rings.
TEST(RingsForHole, IsClampedToTheAllowedRange) {
  ZoneOptions options;
  EXPECT_EQ(rings_for_hole(1, 1, options), 3);  // 1 / 18.02 = 0.06
  EXPECT_EQ(rings_for_hole(0, 1, options), 3);
  EXPECT_EQ(rings_for_hole(1e9, 1, options), 40);
  options.min_rings = 7;
  options.max_rings = 10;
  EXPECT_EQ(rings_for_hole(100, 1, options), 7);   // 5 → 7
  EXPECT_EQ(rings_for_hole(360, 1, options), 10);  // 15 → 10
  options.max_rings = 100;
  EXPECT_EQ(rings_for_hole(1e9, 1, options), 63);  // 1e9 / (0.0159e9 + 18) = 62.9
  EXPECT_THROW(rings_for_hole(100, 0, options), InvalidInput);
}

// With one ring and a flat grid, the zone is exactly the faces touching the hole's boundary
// vertices: nothing is rejected (all normals agree) and no other face has three zone vertices.
TEST(GrowZone, OneRingIsTheFacesTouchingTheBoundary) {
  const int n = 20;
  const Mesh mesh = grid_with_holes(n, {{8, 8, 12, 12}});
  const MeshTopology topology = build_topology(mesh);
  const HoleSet holes = find_holes(mesh, topology);
  const BoundaryLoop& hole = loop_through(holes, grid_id(n, 8, 8));
  ASSERT_EQ(hole.vertices.size(), 16u);
  ZoneOptions options;
  options.rings = 1;
  const Zone zone = zone_of(mesh, hole, options);

  std::vector<int> expected;
  for (int f = 0; f < mesh.face_count(); ++f) {
    for (int v : mesh.triangles[f]) {
      if (std::count(hole.vertices.begin(), hole.vertices.end(), v)) {
        expected.push_back(f);
        break;
      }
    }
  }
  EXPECT_EQ(zone.faces, expected);
  EXPECT_EQ(zone.rings, 1);
  EXPECT_EQ(zone.rings_grown, 1);
  EXPECT_EQ(zone.rejected_faces, 0);
  std::set<int> vertices;
  for (int f : expected) vertices.insert(mesh.triangles[f].begin(), mesh.triangles[f].end());
  EXPECT_EQ(zone.vertices, std::vector<int>(vertices.begin(), vertices.end()));
  // The outer border of the grid is 7 edges away: not reached.
  EXPECT_TRUE(zone.other_holes.empty());
}

// With more rings than the mesh is wide the zone stops at the mesh border: it takes every face,
// and the last ring that grew is the graph distance (edges (±1, 0), (0, ±1), ±(1, 1)) from the
// hole to the farthest vertex, (10, 0) from (4, 2) and (0, 10) from (2, 4): 8 edges.
TEST(GrowZone, StopsGrowingAtTheMeshBorder) {
  const int n = 10;
  const Mesh mesh = grid_with_holes(n, {{2, 2, 4, 4}});
  const HoleSet holes = find_holes(mesh, build_topology(mesh));
  const BoundaryLoop& hole = loop_through(holes, grid_id(n, 2, 2));
  ZoneOptions options;
  options.rings = 20;
  const Zone zone = zone_of(mesh, hole, options);
  EXPECT_EQ(zone.faces.size(), static_cast<size_t>(mesh.face_count()));
  EXPECT_EQ(zone.rings, 20);
  EXPECT_EQ(zone.rings_grown, 8);
  EXPECT_EQ(zone.rejected_faces, 0);

  options.rings = 3;  // fewer rings: the zone ends three edges from the hole
  const Zone small = zone_of(mesh, hole, options);
  EXPECT_EQ(small.rings_grown, 3);
  EXPECT_LT(small.faces.size(), zone.faces.size());
  for (int v : small.vertices) {
    const Vec3& p = mesh.positions[v];
    // Distance in this grid's graph from the square [2, 4]² (dx, dy: signed gaps to it).
    const double dx = p.x() < 2 ? p.x() - 2 : p.x() > 4 ? p.x() - 4 : 0;
    const double dy = p.y() < 2 ? p.y() - 2 : p.y() > 4 ? p.y() - 4 : 0;
    const double steps =
        dx * dy > 0 ? std::max(std::abs(dx), std::abs(dy)) : std::abs(dx) + std::abs(dy);
    EXPECT_LE(steps, 3) << "vertex " << v << " at " << p.transpose();
  }
}

// A grid folded along x = 10 so that the part beyond the fold turns by 120° (normals 120° apart,
// the fold's vertex normals 60° from either side). Every vertex beyond the fold has z > 0.
Mesh folded_grid_with_hole() {
  const int n = 20;
  Mesh mesh = grid_with_holes(n, {{5, 8, 8, 12}});
  const double angle = 120 * M_PI / 180;
  for (Vec3& p : mesh.positions) {
    if (p.x() > 10) {
      const double t = p.x() - 10;
      p = Vec3(10 + t * std::cos(angle), p.y(), t * std::sin(angle));
    }
  }
  return mesh;
}

// Eq. 4: with γ = 75° the faces beyond a 120° fold are refused (a new vertex's normal is about
// 112° from the diffused normal of the fold vertex that reaches it) and the zone stays on the near
// side; with γ = 179° they are accepted.
TEST(GrowZone, NormalDiffusionStopsAtASharpFold) {
  const Mesh mesh = folded_grid_with_hole();
  const HoleSet holes = find_holes(mesh, build_topology(mesh));
  const BoundaryLoop& hole = loop_through(holes, grid_id(20, 5, 8));
  ZoneOptions options;
  options.rings = 6;  // the fold is two edges from the hole
  options.gamma_degrees = 75;
  const Zone strict = zone_of(mesh, hole, options);
  EXPECT_GT(strict.rejected_faces, 0);
  bool reaches_fold = false;
  for (int v : strict.vertices) {
    EXPECT_EQ(mesh.positions[v].z(), 0) << "vertex " << v << " lies beyond the fold";
    reaches_fold |= mesh.positions[v].x() == 10;
  }
  EXPECT_TRUE(reaches_fold);

  options.gamma_degrees = 179;
  const Zone loose = zone_of(mesh, hole, options);
  EXPECT_EQ(loose.rejected_faces, 0);
  const bool beyond = std::any_of(loose.vertices.begin(), loose.vertices.end(),
                                  [&](int v) { return mesh.positions[v].z() > 0; });
  EXPECT_TRUE(beyond);
  EXPECT_GT(loose.faces.size(), strict.faces.size());
  EXPECT_TRUE(std::includes(loose.faces.begin(), loose.faces.end(), strict.faces.begin(),
                            strict.faces.end()));
}

// other_holes lists exactly the loops whose vertices the zone reaches: a second hole three edges
// away is reached with three rings but not with two; the outer border (four edges away) is not.
TEST(GrowZone, ListsTheOtherHolesItReaches) {
  const int n = 20;
  const Mesh mesh = grid_with_holes(n, {{4, 4, 7, 7}, {10, 4, 13, 7}});
  const HoleSet holes = find_holes(mesh, build_topology(mesh));
  ASSERT_EQ(holes.loops.size(), 3u);
  const BoundaryLoop& hole = loop_through(holes, grid_id(n, 4, 4));
  const BoundaryLoop& second = loop_through(holes, grid_id(n, 10, 4));
  ZoneOptions options;
  options.rings = 2;
  EXPECT_TRUE(zone_of(mesh, hole, options).other_holes.empty());
  options.rings = 3;
  EXPECT_EQ(zone_of(mesh, hole, options).other_holes, std::vector<int>{second.id});
  options.rings = 4;  // now the grid's border too
  std::vector<int> both = {second.id, loop_through(holes, grid_id(n, 0, 0)).id};
  std::sort(both.begin(), both.end());
  EXPECT_EQ(zone_of(mesh, hole, options).other_holes, both);
}

}  // namespace
}  // namespace rangefill
