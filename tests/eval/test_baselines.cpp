// CGAL's hole filling as benchmark baselines (baselines.h): both close simple holes, keep the input
// bit for bit and mark what they add.
#include "rangefill/eval/baselines.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "rangefill/core/topology.h"
#include "rangefill/eval/metrics.h"
#include "rangefill/eval/punch.h"
#include "rangefill/hole/holes.h"
#include "support.h"

namespace rangefill {
namespace {

// The unit sphere with two caps cut off: the faces within 0.3 of (0, 0, ±1).
Mesh sphere_with_two_holes() {
  const Mesh sphere = testing::make_sphere(16);
  std::vector<PunchedHole> caps(2);
  for (int f = 0; f < sphere.face_count(); ++f) {
    for (int cap = 0; cap < 2; ++cap) {
      const Vec3 pole(0, 0, cap == 0 ? 1 : -1);
      const Triangle& t = sphere.triangles[f];
      if (std::all_of(t.begin(), t.end(),
                      [&](int v) { return (sphere.positions[v] - pole).norm() < 0.3; })) {
        caps[cap].removed_faces.push_back(f);
      }
    }
  }
  return remove_holes(sphere, caps).mesh;
}

// Largest distance of the generated vertices from the unit sphere.
double off_sphere(const Mesh& mesh, int first_new) {
  double largest = 0;
  for (int v = first_new; v < mesh.vertex_count(); ++v) {
    largest = std::max(largest, std::abs(mesh.positions[v].norm() - 1));
  }
  return largest;
}

// The triangulation alone closes each hole of b boundary vertices with b − 2 triangles and no new
// vertex, keeps the input bit for bit, marks the faces with their loop's id, and the result is a
// closed manifold without self-intersection.
TEST(FillHolesCgal, TriangulationClosesBothHoles) {
  const Mesh mesh = sphere_with_two_holes();
  const HoleSet loops = find_holes(mesh, build_topology(mesh));
  ASSERT_EQ(loops.loops.size(), 2u);
  BaselineOptions options;
  options.method = Baseline::cgal_triangulate;
  const RepairResult result = fill_holes_cgal(mesh, options);
  testing::expect_input_preserved(mesh, result.mesh);
  EXPECT_EQ(result.mesh.vertex_count(), mesh.vertex_count());
  ASSERT_EQ(result.holes.size(), 2u);
  for (const HoleReport& report : result.holes) {
    SCOPED_TRACE("hole " + std::to_string(report.id));
    EXPECT_TRUE(report.filled) << report.failure;
    EXPECT_EQ(report.method, "cgal-triangulate");
    EXPECT_EQ(report.new_vertices, 0);
    EXPECT_EQ(report.new_faces, static_cast<int>(loops.loops[report.loop].vertices.size()) - 2);
    EXPECT_EQ(static_cast<int>(faces_of_hole(result.mesh, report.id).size()), report.new_faces);
  }
  EXPECT_EQ(result.open_count(OpenReason::failed), 0);
  EXPECT_TRUE(check_manifold(result.mesh).closed_manifold());
  EXPECT_EQ(count_self_intersections(result.mesh, faces_of_hole(result.mesh, kAnyHole)), 0);
  ASSERT_EQ(result.restoration_matrix.size(), 3u);
  const int b = static_cast<int>(loops.loops[0].vertices.size());
  EXPECT_EQ(result.restoration_matrix[1][0], 0);
  EXPECT_EQ(result.restoration_matrix[1][1], b - 3);
  EXPECT_EQ(result.restoration_matrix[1][2], b - 2);
}

// Refined and faired, the patch of the one loop asked for gets vertices of its own, near the sphere
// it was cut from (its flat triangulation lies up to 0.045 below it), with edges about as long as
// the mesh's; the other loop stays open.
TEST(FillHolesCgal, FairingClosesTheLoopAskedFor) {
  const Mesh mesh = sphere_with_two_holes();
  BaselineOptions options;
  options.holes = {1};
  const RepairResult result = fill_holes_cgal(mesh, options);
  testing::expect_input_preserved(mesh, result.mesh);
  ASSERT_EQ(result.holes.size(), 1u);
  const HoleReport& report = result.holes[0];
  EXPECT_EQ(report.id, 1);
  EXPECT_TRUE(report.filled) << report.failure;
  EXPECT_EQ(report.method, "cgal-fair");
  EXPECT_GT(report.new_vertices, 10);
  EXPECT_EQ(result.mesh.vertex_count(), mesh.vertex_count() + report.new_vertices);
  EXPECT_LT(off_sphere(result.mesh, mesh.vertex_count()), 0.01);
  const double ratio =
      mean_edge_length(result.mesh, faces_of_hole(result.mesh, 1)) / mean_edge_length(mesh);
  EXPECT_GT(ratio, 0.7);
  EXPECT_LT(ratio, 1.5);
  const ManifoldCheck check = check_manifold(result.mesh);
  EXPECT_EQ(check.boundary_loops, 1);
  EXPECT_EQ(check.nonmanifold_edges + check.misoriented_edges + check.nonmanifold_vertices, 0);
}

// A loop that does not exist, bad options and a mesh CGAL's Surface_mesh cannot hold are refused.
TEST(FillHolesCgal, RefusesWhatItCannotFill) {
  const Mesh mesh = sphere_with_two_holes();
  BaselineOptions options;
  options.holes = {2};
  EXPECT_THROW(fill_holes_cgal(mesh, options), InvalidInput);
  options.holes = {};
  options.fairing_continuity = 3;
  EXPECT_THROW(fill_holes_cgal(mesh, options), InvalidInput);
  Mesh twisted = testing::make_grid(2);
  std::swap(twisted.triangles[0][0], twisted.triangles[0][1]);  // misoriented against its neighbour
  EXPECT_THROW(fill_holes_cgal(twisted, BaselineOptions()), InvalidInput);
  EXPECT_EQ(baseline_from_name(baseline_name(Baseline::cgal_fair)), Baseline::cgal_fair);
  EXPECT_EQ(baseline_from_name(baseline_name(Baseline::cgal_triangulate)),
            Baseline::cgal_triangulate);
  EXPECT_THROW(baseline_from_name("meshlab"), InvalidInput);
}

}  // namespace
}  // namespace rangefill
