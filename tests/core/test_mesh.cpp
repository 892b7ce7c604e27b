#include "rangefill/core/mesh.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "support.h"

namespace rangefill {
namespace {

double total_area(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles) {
  double area = 0;
  for (const Triangle& t : triangles) {
    area +=
        0.5 * (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]).norm();
  }
  return area;
}

TEST(Mesh, MeanEdgeLengthCountsEachEdgeOnce) {
  // A 1x1 grid: 4 unit sides and one diagonal.
  EXPECT_NEAR(mean_edge_length(testing::make_grid(1)), (4 + std::sqrt(2.0)) / 5, 1e-15);
  // 2x2: 12 unit edges, 4 diagonals.
  EXPECT_NEAR(mean_edge_length(testing::make_grid(2)), (12 + 4 * std::sqrt(2.0)) / 16, 1e-15);
}

TEST(Mesh, AddVertexAndFaceKeepEveryArrayInStep) {
  Mesh mesh = testing::make_cube();
  mesh.colors.assign(8, Rgb(0.5f, 0.5f, 0.5f));
  mesh.vertex_properties.push_back({"quality", ScalarType::float32, std::vector<double>(8, 2.0)});
  mesh.face_properties.push_back({"label", ScalarType::int32, std::vector<double>(12, 7.0)});
  const int v = add_vertex(mesh, Vec3(2, 2, 2), 3, Rgb(1, 0, 0));
  const int f = add_face(mesh, {0, 1, v}, 3);
  EXPECT_EQ(v, 8);
  EXPECT_EQ(f, 12);
  EXPECT_EQ(mesh.vertex_hole[v], 3);
  EXPECT_EQ(mesh.face_hole[f], 3);
  EXPECT_EQ(mesh.colors[v], Rgb(1, 0, 0));
  EXPECT_EQ(mesh.vertex_properties[0].values.back(), 0.0);
  EXPECT_EQ(mesh.face_properties[0].values.back(), 0.0);
  EXPECT_NO_THROW(validate_mesh(mesh, "mesh"));
}

TEST(Mesh, ValidateNamesTheProblem) {
  Mesh mesh = testing::make_cube();
  mesh.triangles[5] = {0, 1, 8};
  try {
    validate_mesh(mesh, "cube.ply");
    FAIL() << "no exception";
  } catch (const InvalidInput& error) {
    EXPECT_STREQ(error.what(), "cube.ply: face 5 refers to vertex 8, out of range [0, 8)");
  }
  mesh = testing::make_cube();
  mesh.positions[3].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(validate_mesh(mesh, "cube.ply"), InvalidInput);
  mesh = testing::make_cube();
  mesh.triangles[0] = {0, 2, 0};
  EXPECT_THROW(validate_mesh(mesh, "cube.ply"), InvalidInput);
  mesh = testing::make_cube();
  mesh.normals.resize(3);
  EXPECT_THROW(validate_mesh(mesh, "cube.ply"), InvalidInput);
}

TEST(TriangulatePolygon, ConcavePolygonKeepsItsArea) {
  // An L shape (area 3) in a tilted plane: a fan from vertex 0 would overlap outside it.
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<Vec3> positions;
  for (const auto& [x, y] :
       std::vector<std::pair<double, double>>{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}) {
    positions.push_back(tilt * Vec3(x, y, 0));
  }
  const std::vector<int> polygon = {3, 4, 5, 0, 1, 2};  // starts at the reflex corner
  const std::vector<Triangle> triangles = triangulate_polygon(positions, polygon);
  ASSERT_EQ(triangles.size(), 4u);
  EXPECT_NEAR(total_area(positions, triangles), 3.0, 1e-12);
  // Every triangle keeps the polygon's orientation.
  const Vec3 normal = tilt * Vec3::UnitZ();
  for (const Triangle& t : triangles) {
    EXPECT_GT(
        (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]).dot(normal),
        0);
  }
}

TEST(TriangulatePolygon, DegeneratePolygonStillYieldsNMinusTwoTriangles) {
  const std::vector<Vec3> positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  EXPECT_EQ(triangulate_polygon(positions, {0, 1, 2, 3}).size(), 2u);
}

// extract_faces renumbers vertices in first-use order and keeps positions and orientation.
TEST(ExtractFaces, RenumbersInFirstUseOrder) {
  const Mesh cube = testing::make_cube();
  // Faces 3 = {5, 7, 6} and 2 = {4, 5, 6}, in that order: 5 → 0, 7 → 1, 6 → 2, 4 → 3.
  const Mesh top = extract_faces(cube, {3, 2});
  ASSERT_EQ(top.vertex_count(), 4);
  EXPECT_EQ(top.triangles, (std::vector<Triangle>{{0, 1, 2}, {3, 0, 2}}));
  EXPECT_EQ(top.positions[0], cube.positions[5]);
  EXPECT_EQ(top.positions[1], cube.positions[7]);
  EXPECT_EQ(top.positions[2], cube.positions[6]);
  EXPECT_EQ(top.positions[3], cube.positions[4]);
  EXPECT_EQ(top.face_hole, std::vector<int>(2, kOriginal));
  EXPECT_EQ(extract_faces(cube, {}).vertex_count(), 0);
}

}  // namespace
}  // namespace rangefill
