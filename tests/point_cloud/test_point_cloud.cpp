// Meshing point clouds (point_cloud.h): the greedy projection on clouds sampled from built
// surfaces, made an oriented edge-manifold, then repaired.
#include "rangefill/point_cloud/point_cloud.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "rangefill/eval/metrics.h"
#include "rangefill/repair/pipeline.h"
#include "support.h"

namespace rangefill {
namespace {

// make_sphere_cloud, with or without the sphere's normals.
Mesh capless_sphere_cloud(double cut, bool with_normals) {
  Mesh cloud = testing::make_sphere_cloud(3000, cut);
  if (with_normals) cloud.normals = cloud.positions;  // the unit sphere's outward normals
  return cloud;
}

TEST(MeanPointSpacing, IsTheNearestNeighbourDistance) {
  const Mesh grid = testing::make_grid(10);  // spacing 1
  EXPECT_NEAR(mean_point_spacing(grid.positions), 1.0, 1e-6);
  EXPECT_EQ(mean_point_spacing({Vec3::Zero()}), 0.0);
}

class MeshPointCloud : public ::testing::TestWithParam<bool> {};

// The points come back bit for bit, joined into an edge-manifold oriented outwards whose longest
// boundary loop runs along the cut; the repair closes every loop, onto the sphere.
TEST_P(MeshPointCloud, SphereWithACapCutOutIsMeshedAndRepaired) {
  const double cut = 0.85;
  const Mesh cloud = capless_sphere_cloud(cut, GetParam());
  const Mesh mesh = mesh_point_cloud(cloud);
  testing::expect_bit_identical(mesh.positions, cloud.positions);
  EXPECT_EQ(mesh.normals.size(), cloud.normals.size());
  ASSERT_GT(mesh.face_count(), 19 * cloud.vertex_count() / 10);  // about two faces per point
  const ManifoldCheck check = check_manifold(mesh);
  EXPECT_EQ(check.nonmanifold_edges + check.misoriented_edges + check.nonmanifold_vertices, 0);
  double lowest_cosine = 1;  // between a face's normal and the sphere's: > 0, outwards
  for (int f = 0; f < mesh.face_count(); ++f) {
    lowest_cosine =
        std::min(lowest_cosine,
                 triangle_cross(mesh, f).normalized().dot(mesh.positions[mesh.triangles[f][0]]));
  }
  EXPECT_GT(lowest_cosine, 0.0);
  const double spacing = mean_point_spacing(cloud.positions);
  const HoleSet holes = find_holes(mesh, build_topology(mesh));
  const BoundaryLoop& longest = *std::max_element(
      holes.loops.begin(), holes.loops.end(),
      [](const auto& a, const auto& b) { return a.vertices.size() < b.vertices.size(); });
  for (int v : longest.vertices) EXPECT_GT(mesh.positions[v].z(), cut - 2 * spacing);
  std::printf("%d points, %d faces, %zu boundary loops\n", cloud.vertex_count(), mesh.face_count(),
              holes.loops.size());

  const RepairOptions options = testing::paper_chain(testing::plane_options("mls"));
  const RepairResult result = repair(mesh, options);
  testing::expect_input_preserved(mesh, result.mesh);
  EXPECT_TRUE(check_manifold(result.mesh).closed_manifold());
  double worst = 0;
  for (int v = mesh.vertex_count(); v < result.mesh.vertex_count(); ++v) {
    worst = std::max(worst, std::abs(result.mesh.positions[v].norm() - 1));
  }
  // The cap (32°) comes back on the sphere, within 0.1 d_m, as the caps of
  // Pipeline.MlsBringsSphereCapsBack do.
  const double d_m = mean_edge_length(mesh);
  std::printf("generated vertices within %.2f d_m of the sphere\n", worst / d_m);
  EXPECT_LT(worst, 0.1 * d_m);
}

INSTANTIATE_TEST_SUITE_P(PointCloud, MeshPointCloud, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Normals" : "NoNormals"; });

TEST(MeshPointCloud, RefusesMeshesAndTinyClouds) {
  EXPECT_THROW(mesh_point_cloud(testing::make_cube()), InvalidInput);
  Mesh two;
  add_vertex(two, Vec3::Zero(), kOriginal);
  add_vertex(two, Vec3::UnitX(), kOriginal);
  EXPECT_THROW(mesh_point_cloud(two), InvalidInput);
  GreedyMeshingOptions options;
  options.mu = 0;
  EXPECT_THROW(mesh_point_cloud(capless_sphere_cloud(0.85, false), options), InvalidInput);
}

TEST(Mesher, Names) {
  EXPECT_EQ(mesher_from_name("greedy"), Mesher::greedy);
  EXPECT_EQ(mesher_from_name("none"), Mesher::none);
  EXPECT_EQ(mesher_name(Mesher::greedy), "greedy");
  EXPECT_THROW(mesher_from_name("poisson"), InvalidInput);
}

}  // namespace
}  // namespace rangefill
