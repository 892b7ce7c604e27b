// Triangulation and stitching (stitch.h, Section VIII): the grid triangulation T1 (eq. 14–15), the
// least-area triangulation of a loop with forbidden chords, and T1 ∪ T2 on a flat sheet.
#include "rangefill/image/stitch.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "rangefill/eval/metrics.h"
#include "support.h"

namespace rangefill {
namespace {

// A patch whose pixel (row, col) is present where `present` has a non-space character; points are
// numbered in row-major order and placed at (col, −row, 0) (the image plane with y up).
Patch hand_patch(const std::vector<std::string>& present) {
  Patch patch;
  patch.index = cv::Mat(static_cast<int>(present.size()), static_cast<int>(present[0].size()),
                        CV_32S, cv::Scalar(-1));
  for (int row = 0; row < patch.index.rows; ++row) {
    for (int col = 0; col < patch.index.cols; ++col) {
      if (present[row][col] == ' ') continue;
      patch.index.at<int>(row, col) = static_cast<int>(patch.points.size());
      patch.points.emplace_back(col, -row, 0);
      patch.pixels.emplace_back(col, row);
    }
  }
  return patch;
}

// Twice the signed area of a triangle of the patch in the image plane with y up.
double signed_area2(const Patch& patch, const Triangle& t) {
  const Vec3 &a = patch.points[t[0]], &b = patch.points[t[1]], &c = patch.points[t[2]];
  return (b - a).cross(c - a).z();
}

// A full 3×3 block: four 2×2 blocks, two triangles each, all counter-clockwise with y up, each
// split by its lower-left to upper-right diagonal; together they cover the 2×2 square once.
TEST(TriangulateGrid, FullBlockGivesTwoTrianglesPerCellOnOneDiagonal) {
  const Patch patch = hand_patch({"xxx", "xxx", "xxx"});
  const std::vector<Triangle> triangles = triangulate_grid(patch);
  ASSERT_EQ(triangles.size(), 8u);
  double area = 0;
  std::map<std::pair<int, int>, int> per_cell;
  for (const Triangle& t : triangles) {
    EXPECT_EQ(signed_area2(patch, t), 1) << "clockwise or not a half-cell";
    area += signed_area2(patch, t) / 2;
    int row_min = 9, col_min = 9;
    for (int v : t) {
      row_min = std::min(row_min, patch.pixels[v].y);
      col_min = std::min(col_min, patch.pixels[v].x);
    }
    ++per_cell[{row_min, col_min}];
    // The diagonal: upper-right (row_min, col_min + 1) and lower-left (row_min + 1, col_min).
    const int upper_right = patch.index.at<int>(row_min, col_min + 1);
    const int lower_left = patch.index.at<int>(row_min + 1, col_min);
    EXPECT_TRUE(std::count(t.begin(), t.end(), upper_right) &&
                std::count(t.begin(), t.end(), lower_left));
  }
  EXPECT_EQ(area, 4);
  EXPECT_EQ(per_cell.size(), 4u);
  for (const auto& [cell, count] : per_cell) EXPECT_EQ(count, 2);
}

// Three present pixels of a 2×2 block, in any of the four L shapes, give one counter-clockwise
// triangle; two pixels (a diagonal) or one give none.
TEST(TriangulateGrid, ThreePixelsGiveOneTriangle) {
  for (const std::vector<std::string>& shape : std::vector<std::vector<std::string>>{
           {"x ", "xx"}, {"xx", " x"}, {"xx", "x "}, {" x", "xx"}}) {
    const Patch patch = hand_patch(shape);
    const std::vector<Triangle> triangles = triangulate_grid(patch);
    ASSERT_EQ(triangles.size(), 1u) << shape[0] << "|" << shape[1];
    EXPECT_EQ(signed_area2(patch, triangles[0]), 1) << shape[0] << "|" << shape[1];
    std::array<int, 3> sorted = triangles[0];
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, (std::array<int, 3>{0, 1, 2}));
  }
  EXPECT_TRUE(triangulate_grid(hand_patch({"x ", " x"})).empty());
  EXPECT_TRUE(triangulate_grid(hand_patch({" x", "x "})).empty());
  EXPECT_TRUE(triangulate_grid(hand_patch({"x  ", "  x"})).empty());
}

// A ragged patch: every 2×2 block with 4 pixels gives 2 triangles, with 3 gives 1, else none.
TEST(TriangulateGrid, CountsFollowTheBlocks) {
  const Patch patch = hand_patch({"xxx ", "xx x", " xxx"});
  // Pixels present per block (top-left corner row, col): (0, 0) 4 → 2 triangles; (0, 1) 3 → 1;
  // (0, 2) 2 on a diagonal → 0; (1, 0), (1, 1), (1, 2) 3 each → 1 each: 6 in all.
  const std::vector<Triangle> triangles = triangulate_grid(patch);
  EXPECT_EQ(triangles.size(), 6u);
  for (const Triangle& t : triangles) EXPECT_EQ(signed_area2(patch, t), 1);
}

// T1 ∪ T2 on a flat sheet seen along its normal: the fill passes fill_defect (its triangles
// facing the viewer), covers exactly the hole's area, and merged with the sheet leaves only the
// outer border open, without intersections.
TEST(Stitch, FlatSheetHoleIsCoveredExactly) {
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.6, Vec3(1, 1, -2).normalized()).toRotationMatrix();
  Mesh grid = testing::make_grid(24);
  for (Vec3& p : grid.positions) p = rotation * p;
  const Mesh sheet = testing::remove_faces(grid, [&](const Vec3& p) {
    return (rotation.transpose() * p - Vec3(11.7, 12.2, 0)).norm() < 6;
  });
  const MeshTopology topology = build_topology(sheet);
  const BoundaryLoop hole = testing::inner_loop(sheet);
  Zone zone;
  for (int f = 0; f < sheet.face_count(); ++f) zone.faces.push_back(f);
  for (int v = 0; v < sheet.vertex_count(); ++v) zone.vertices.push_back(v);
  Frame frame;
  frame.rotation = rotation.transpose();
  const RangeImage image =
      rasterize_zone(sheet, zone, hole, hole_in_plane(sheet, hole, frame), mean_edge_length(sheet));
  const Patch patch = back_project(image, image.depth);
  const FillOutcome outcome = stitch(sheet, topology, hole, hole_in_plane(sheet, hole, frame),
                                     patch, triangulate_grid(patch));
  ASSERT_TRUE(std::holds_alternative<Fill>(outcome));
  const Fill& fill = std::get<Fill>(outcome);

  EXPECT_EQ(fill.boundary, hole.vertices);
  EXPECT_EQ(fill.points.size(), patch.points.size());  // every grid point is used
  Mesh merged = sheet;
  std::vector<int> id = fill.boundary;
  for (const Vec3& p : fill.points) id.push_back(add_vertex(merged, p, 0));
  double area = 0;
  std::vector<int> fill_faces;
  for (const Triangle& t : fill.triangles) {
    fill_faces.push_back(add_face(merged, {id[t[0]], id[t[1]], id[t[2]]}, 0));
    const Vec3 cross = triangle_cross(merged, fill_faces.back());
    EXPECT_GT(cross.dot(frame.normal()), 0);
    area += 0.5 * cross.norm();
  }
  const double hole_area = std::abs(polygon_area(hole_in_plane(sheet, hole, frame).loop));
  EXPECT_NEAR(area, hole_area, 1e-9 * hole_area);
  EXPECT_NEAR(hole.area, hole_area, 1e-9 * hole_area);
  const ManifoldCheck check = check_manifold(merged);
  EXPECT_EQ(check.boundary_loops, 1);
  EXPECT_EQ(check.nonmanifold_edges + check.misoriented_edges + check.nonmanifold_vertices, 0);
  EXPECT_EQ(count_self_intersections(merged, fill_faces), 0);
}

}  // namespace
}  // namespace rangefill
