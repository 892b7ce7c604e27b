// Punching holes (punch.h): determinism, one simple boundary loop per hole (disks and elongated
// holes), holes kept apart, curvature classes, vertex bookkeeping and remove_holes.
#include "rangefill/eval/punch.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "rangefill/eval/metrics.h"
#include "rangefill/hole/holes.h"
#include "support.h"

namespace rangefill {
namespace {

PunchOptions options_with_seed(std::uint64_t seed) {
  PunchOptions options;
  options.holes = 5;
  options.seed = seed;
  options.min_radius = 2;
  options.max_radius = 5;
  return options;
}

const Mesh& sphere() {
  static const Mesh mesh = testing::make_sphere(16);  // 5120 faces, d_m ≈ 0.067
  return mesh;
}

bool same_mesh(const Mesh& a, const Mesh& b) {
  return a.positions.size() == b.positions.size() && a.triangles == b.triangles &&
         std::memcmp(a.positions.data(), b.positions.data(), sizeof(Vec3) * a.positions.size()) ==
             0;
}

// The same seed gives the same holes and mesh, bit for bit; another seed other holes.
TEST(PunchHoles, IsDeterministicForASeed) {
  const PunchResult first = punch_holes(sphere(), options_with_seed(7));
  const PunchResult again = punch_holes(sphere(), options_with_seed(7));
  const PunchResult other = punch_holes(sphere(), options_with_seed(8));
  ASSERT_EQ(first.holes.size(), 5u);
  ASSERT_EQ(again.holes.size(), first.holes.size());
  EXPECT_TRUE(same_mesh(first.mesh, again.mesh));
  EXPECT_EQ(first.original_vertex, again.original_vertex);
  for (size_t h = 0; h < first.holes.size(); ++h) {
    EXPECT_EQ(first.holes[h].centre, again.holes[h].centre);
    EXPECT_EQ(first.holes[h].radius, again.holes[h].radius);
    EXPECT_EQ(first.holes[h].removed_faces, again.holes[h].removed_faces);
  }
  EXPECT_FALSE(same_mesh(first.mesh, other.mesh));
  EXPECT_NE(first.holes[0].centre, other.holes[0].centre);
}

// Each punched hole leaves one boundary loop through distinct vertices, so there are as many loops
// as holes; the removed regions are disks (Euler characteristic 1, one border loop) of the given
// radius, pairwise disjoint and without a common vertex; faces removed and faces kept add up.
TEST(PunchHoles, LeavesOneSimpleLoopPerHoleAndKeepsHolesApart) {
  for (std::uint64_t seed : {1, 2, 3}) {
    const PunchResult result = punch_holes(sphere(), options_with_seed(seed));
    ASSERT_GE(result.holes.size(), 3u) << "seed " << seed;
    const HoleSet loops = find_holes(result.mesh, build_topology(result.mesh));
    EXPECT_EQ(loops.loops.size(), result.holes.size()) << "seed " << seed;
    for (const BoundaryLoop& loop : loops.loops) {
      const std::set<int> distinct(loop.vertices.begin(), loop.vertices.end());
      EXPECT_EQ(distinct.size(), loop.vertices.size()) << "seed " << seed;
    }
    EXPECT_TRUE(loops.pinched_vertices.empty());

    const double mean_edge = mean_edge_length(sphere());
    std::set<int> used_faces, used_vertices;
    size_t removed = 0;
    for (const PunchedHole& hole : result.holes) {
      EXPECT_TRUE(std::is_sorted(hole.removed_faces.begin(), hole.removed_faces.end()));
      EXPECT_GE(hole.radius, 2 * mean_edge);
      EXPECT_LE(hole.radius, 5 * mean_edge);
      std::set<int> vertices;
      for (int f : hole.removed_faces) {
        EXPECT_TRUE(used_faces.insert(f).second) << "face " << f << " removed twice";
        for (int v : sphere().triangles[f]) {
          vertices.insert(v);
          // Geodesic distance along edges is at least the straight one.
          EXPECT_LT((sphere().positions[v] - sphere().positions[hole.centre]).norm(), hole.radius);
        }
      }
      for (int v : vertices) EXPECT_TRUE(used_vertices.insert(v).second) << "vertex " << v;
      const Mesh disk = extract_faces(sphere(), hole.removed_faces);
      const MeshTopology topology = build_topology(disk);
      EXPECT_EQ(disk.vertex_count() - topology.edge_count + disk.face_count(), 1);
      EXPECT_EQ(find_holes(disk, topology).loops.size(), 1u);
      removed += hole.removed_faces.size();
    }
    EXPECT_EQ(result.mesh.face_count() + removed, sphere().triangles.size());
  }
}

// original_vertex maps each kept vertex to an input vertex with the same position, in increasing
// order; the kept faces are the input's faces in their order, renumbered; the vertices dropped are
// exactly the inner vertices of the removed disks.
TEST(PunchHoles, OriginalVertexMapsBackToTheInput) {
  const PunchResult result = punch_holes(sphere(), options_with_seed(4));
  ASSERT_EQ(result.original_vertex.size(), result.mesh.positions.size());
  EXPECT_TRUE(std::is_sorted(result.original_vertex.begin(), result.original_vertex.end()));
  for (int v = 0; v < result.mesh.vertex_count(); ++v) {
    const Vec3& input = sphere().positions[result.original_vertex[v]];
    EXPECT_EQ(std::memcmp(input.data(), result.mesh.positions[v].data(), sizeof(Vec3)), 0);
  }
  std::set<int> removed;
  for (const PunchedHole& hole : result.holes)
    removed.insert(hole.removed_faces.begin(), hole.removed_faces.end());
  std::vector<Triangle> expected;
  std::set<int> kept_vertices;
  for (int f = 0; f < static_cast<int>(sphere().triangles.size()); ++f) {
    if (removed.count(f)) continue;
    expected.push_back(sphere().triangles[f]);
    kept_vertices.insert(expected.back().begin(), expected.back().end());
  }
  ASSERT_EQ(result.mesh.triangles.size(), expected.size());
  for (size_t f = 0; f < expected.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(result.original_vertex[result.mesh.triangles[f][k]], expected[f][k]);
    }
  }
  EXPECT_EQ(std::set<int>(result.original_vertex.begin(), result.original_vertex.end()),
            kept_vertices);
}

// Bad radii, aspects, thresholds and an empty list of shapes are refused; a mesh without vertices
// too.
TEST(PunchHoles, RefusesBadOptions) {
  PunchOptions options;
  options.min_radius = 0;
  EXPECT_THROW(punch_holes(sphere(), options), InvalidInput);
  options.min_radius = 4;
  options.max_radius = 3;
  EXPECT_THROW(punch_holes(sphere(), options), InvalidInput);
  EXPECT_THROW(punch_holes(Mesh(), PunchOptions()), InvalidInput);
  for (auto spoil : std::vector<void (*)(PunchOptions&)>{
           [](PunchOptions& o) { o.shapes.clear(); }, [](PunchOptions& o) { o.min_aspect = 0; },
           [](PunchOptions& o) { o.max_aspect = 1.5; },
           [](PunchOptions& o) { o.high_bending = o.low_bending / 2; },
           [](PunchOptions& o) { o.separation = -1; }}) {
    PunchOptions bad;
    spoil(bad);
    EXPECT_THROW(punch_holes(sphere(), bad), InvalidInput);
  }
}

const Mesh& fine_sphere() {
  static const Mesh mesh = testing::make_sphere(32);  // 20480 faces, d_m ≈ 0.033
  return mesh;
}

PunchOptions elongated_options(std::uint64_t seed) {
  PunchOptions options = options_with_seed(seed);
  options.holes = 4;
  options.min_radius = 8;
  options.max_radius = 10;
  options.min_aspect = options.max_aspect = 0.25;
  options.shapes = {HoleShape::elongated};
  return options;
}

// The largest straight distance between two vertices of the faces.
double diameter(const Mesh& mesh, const std::vector<int>& faces) {
  std::set<int> vertices;
  for (int f : faces) vertices.insert(mesh.triangles[f].begin(), mesh.triangles[f].end());
  double largest = 0;
  for (int a : vertices) {
    for (int b : vertices)
      largest = std::max(largest, (mesh.positions[a] - mesh.positions[b]).norm());
  }
  return largest;
}

// Elongated holes: the same seed gives the same holes; each leaves one boundary loop through
// distinct vertices, its region a disk (Euler characteristic 1) about as long as its path plus
// twice its half-width, and more than twice as long as it is wide.
TEST(PunchHoles, ElongatedHolesAreLongSimpleDisks) {
  const double mean_edge = mean_edge_length(fine_sphere());
  const PunchResult result = punch_holes(fine_sphere(), elongated_options(5));
  const PunchResult again = punch_holes(fine_sphere(), elongated_options(5));
  ASSERT_EQ(result.holes.size(), 4u);
  EXPECT_TRUE(same_mesh(result.mesh, again.mesh));
  const HoleSet loops = find_holes(result.mesh, build_topology(result.mesh));
  EXPECT_EQ(loops.loops.size(), 4u);
  for (const BoundaryLoop& loop : loops.loops) {
    EXPECT_EQ(std::set<int>(loop.vertices.begin(), loop.vertices.end()).size(),
              loop.vertices.size());
  }
  for (size_t h = 0; h < result.holes.size(); ++h) {
    const PunchedHole& hole = result.holes[h];
    SCOPED_TRACE("hole " + std::to_string(h));
    EXPECT_EQ(hole.shape, HoleShape::elongated);
    EXPECT_EQ(hole.removed_faces, again.holes[h].removed_faces);
    // Half-width w = 0.25·L, L in [8, 10] d_m.
    EXPECT_GE(hole.radius, 2 * mean_edge * (1 - 1e-12));
    EXPECT_LE(hole.radius, 2.5 * mean_edge * (1 + 1e-12));
    // Path of 2·(L − w) with L in [8, 10] d_m and w = 2..2.5 d_m, ending at 80–100 % of it.
    EXPECT_GE(hole.length, 0.8 * 2 * (8 - 2.5) * mean_edge);
    EXPECT_LE(hole.length, 2 * (10 - 2) * mean_edge);
    const double length = diameter(fine_sphere(), hole.removed_faces);
    EXPECT_GT(length, hole.length);
    EXPECT_LT(length, hole.length + 2 * hole.radius + 2 * mean_edge);
    EXPECT_GT(length, 2 * (2 * hole.radius));
    const Mesh disk = extract_faces(fine_sphere(), hole.removed_faces);
    const MeshTopology topology = build_topology(disk);
    EXPECT_EQ(disk.vertex_count() - topology.edge_count + disk.face_count(), 1);
  }
}

// On the unit sphere both principal curvatures are 1, so a region bends by about sqrt(area / π),
// the radius of a disk of its area; the class follows the thresholds; no edge of a fine sphere is
// sharp.
TEST(PunchHoles, SphereRegionsBendByTheirRadius) {
  PunchOptions options = elongated_options(6);
  options.shapes = {HoleShape::disk, HoleShape::elongated};
  options.min_radius = 3;
  options.max_radius = 20;
  const PunchResult result = punch_holes(fine_sphere(), options);
  ASSERT_EQ(result.holes.size(), 4u);
  EXPECT_EQ(result.holes[0].shape, HoleShape::disk);
  EXPECT_EQ(result.holes[1].shape, HoleShape::elongated);
  for (const PunchedHole& hole : result.holes) {
    double area = 0;
    for (int f : hole.removed_faces) area += 0.5 * triangle_cross(fine_sphere(), f).norm();
    EXPECT_DOUBLE_EQ(hole.area, area);
    EXPECT_NEAR(hole.bending, std::sqrt(area / M_PI), 0.1 * std::sqrt(area / M_PI));
    const CurvatureClass expected = hole.bending < options.low_bending    ? CurvatureClass::low
                                    : hole.bending < options.high_bending ? CurvatureClass::medium
                                                                          : CurvatureClass::high;
    EXPECT_EQ(hole.curvature, expected);
    EXPECT_FALSE(hole.sharp_feature);
  }
}

// With `spread`, on a box (flat sides, sharp edges, corners) made of 24×24 grids: hole 0 is looked
// for where the surface is flat and found there, hole 3 on a sharp feature; the holes of kinds 1
// and 2 (medium and high curvature) are found where the sides meet.
TEST(PunchHoles, SpreadFindsEachKindOfRegion) {
  const Mesh box = testing::make_box(24);
  PunchOptions options = options_with_seed(2);
  options.holes = 4;
  options.max_radius = 4;
  options.separation = 2;
  options.spread = true;
  const PunchResult result = punch_holes(box, options);
  ASSERT_EQ(result.holes.size(), 4u);
  EXPECT_EQ(result.holes[0].curvature, CurvatureClass::low);
  EXPECT_NEAR(result.holes[0].bending, 0, 1e-6);
  EXPECT_FALSE(result.holes[0].sharp_feature);
  EXPECT_EQ(result.holes[1].curvature, CurvatureClass::medium);
  EXPECT_EQ(result.holes[2].curvature, CurvatureClass::high);
  EXPECT_TRUE(result.holes[3].sharp_feature);
  const HoleSet loops = find_holes(result.mesh, build_topology(result.mesh));
  EXPECT_EQ(loops.loops.size(), 4u);
}

// remove_holes removes the given faces and the vertices only they use, sorts each hole's faces and
// sets its area; a face in two holes or out of range is refused.
TEST(RemoveHoles, RemovesTheGivenRegions) {
  const Mesh cube = testing::make_cube();
  PunchedHole top;
  top.removed_faces = {3, 2};  // z = 1: vertices 4, 5, 6, 7, all still used by the sides
  top.bending = 7;             // kept as given
  const PunchResult result = remove_holes(cube, {top});
  ASSERT_EQ(result.holes.size(), 1u);
  EXPECT_EQ(result.holes[0].removed_faces, (std::vector<int>{2, 3}));
  EXPECT_DOUBLE_EQ(result.holes[0].area, 1);
  EXPECT_EQ(result.holes[0].bending, 7);
  EXPECT_EQ(result.mesh.face_count(), 10);
  EXPECT_EQ(result.mesh.vertex_count(), 8);
  PunchedHole again;
  again.removed_faces = {2};
  EXPECT_THROW(remove_holes(cube, {top, again}), InvalidInput);
  again.removed_faces = {12};
  EXPECT_THROW(remove_holes(cube, {again}), InvalidInput);
}

// Names of shapes and classes, both ways.
TEST(PunchHoles, NamesShapesAndClasses) {
  EXPECT_EQ(shape_from_name(shape_name(HoleShape::disk)), HoleShape::disk);
  EXPECT_EQ(shape_from_name(shape_name(HoleShape::elongated)), HoleShape::elongated);
  EXPECT_THROW(shape_from_name("square"), InvalidInput);
  EXPECT_EQ(curvature_name(CurvatureClass::low), "low");
  EXPECT_EQ(curvature_name(CurvatureClass::medium), "medium");
  EXPECT_EQ(curvature_name(CurvatureClass::high), "high");
}

}  // namespace
}  // namespace rangefill
