// Discrete curvature (curvature.h) against surfaces whose curvature is known: a sphere, a plane, a
// cylinder; dihedral angles of a cube.
#include "rangefill/eval/curvature.h"

#include <cmath>

#include <gtest/gtest.h>

#include "support.h"

namespace rangefill {
namespace {

// On the unit sphere K = H = 1 and both principal curvatures are 1; the angle defects add up to
// 4π (Gauss–Bonnet: 2π times the Euler characteristic, exactly for any closed triangulation) and
// the mixed areas to the area of the mesh.
TEST(VertexCurvature, UnitSphereHasCurvatureOne) {
  const Mesh sphere = testing::make_sphere(16);
  const VertexCurvature c = vertex_curvature(sphere, build_topology(sphere));
  double defect = 0, area = 0, mesh_area = 0;
  for (int v = 0; v < sphere.vertex_count(); ++v) {
    EXPECT_NEAR(c.gaussian[v], 1, 0.08) << v;
    EXPECT_NEAR(c.mean[v], 1, 0.04) << v;
    EXPECT_NEAR(c.max_principal(v), 1, 0.2) << v;
    defect += c.gaussian[v] * c.area[v];
    area += c.area[v];
  }
  for (int f = 0; f < sphere.face_count(); ++f) mesh_area += 0.5 * triangle_cross(sphere, f).norm();
  EXPECT_NEAR(defect, 4 * M_PI, 1e-9);
  EXPECT_NEAR(area, mesh_area, 1e-9 * mesh_area);
}

// Inside a flat grid every curvature is 0; on its border the defect is taken from π, so the border
// vertices of a straight side are flat too.
TEST(VertexCurvature, FlatGridHasNone) {
  const Mesh grid = testing::make_grid(6);
  const VertexCurvature c = vertex_curvature(grid, build_topology(grid));
  for (int v = 0; v < grid.vertex_count(); ++v) {
    const int x = v % 7, y = v / 7;
    const bool corner = (x == 0 || x == 6) && (y == 0 || y == 6);
    if (!corner) {
      EXPECT_NEAR(c.gaussian[v], 0, 1e-12) << v;
    }
    if (x > 0 && x < 6 && y > 0 && y < 6) {
      EXPECT_NEAR(c.mean[v], 0, 1e-12) << v;
      EXPECT_NEAR(c.max_principal(v), 0, 1e-6) << v;
    }
  }
}

// On the cylinder of a capsule of radius 0.5 the principal curvatures are 2 and 0: K = 0, H = 1.
TEST(VertexCurvature, CylinderBendsOneWay) {
  const Mesh capsule = testing::make_capsule(0.5, 1, 0.05);
  const VertexCurvature c = vertex_curvature(capsule, build_topology(capsule));
  int checked = 0;
  for (int v = 0; v < capsule.vertex_count(); ++v) {
    if (std::abs(capsule.positions[v].z()) > 0.8) continue;  // away from the caps
    ++checked;
    EXPECT_NEAR(c.gaussian[v], 0, 0.05) << v;
    EXPECT_NEAR(c.mean[v], 1, 0.02) << v;
    EXPECT_NEAR(c.max_principal(v), 2, 0.25) << v;
  }
  EXPECT_GT(checked, 100);
}

// The cube's 12 edges fold by 90°, the diagonals of its sides not at all.
TEST(DihedralAngles, CubeEdgesAreRightAngles) {
  const Mesh cube = testing::make_cube();
  const std::vector<double> angles = dihedral_angles(cube, build_edges(cube, build_topology(cube)));
  ASSERT_EQ(angles.size(), 18u);
  int right = 0, flat = 0;
  for (double angle : angles) {
    right += std::abs(angle - M_PI / 2) < 1e-12;
    flat += std::abs(angle) < 1e-12;
  }
  EXPECT_EQ(right, 12);
  EXPECT_EQ(flat, 6);
}

// An edge with one face has no dihedral angle.
TEST(DihedralAngles, BorderEdgesAreZero) {
  const Mesh grid = testing::make_grid(1);
  const std::vector<double> angles = dihedral_angles(grid, build_edges(grid, build_topology(grid)));
  for (size_t e = 0; e < angles.size(); ++e) EXPECT_EQ(angles[e], 0) << e;
}

}  // namespace
}  // namespace rangefill
