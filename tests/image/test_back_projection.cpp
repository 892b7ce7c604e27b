// Back-projection (back_projection.h, eq. 13): restored pixels of a flat sheet go back onto the
// sheet, points too close to the hole boundary are dropped, and the patch's bookkeeping.
#include "rangefill/image/back_projection.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "support.h"

namespace rangefill {
namespace {

// A 30×30 grid, rotated and moved, without the faces inside a disk of radius 6.5; its zone is
// every face.
// A 30×30 sheet, tilted and moved, with a hole of radius 6.5 off the grid's lines.
testing::TiltedSheet tilted_sheet() {
  return testing::make_tilted_sheet(
      30, Eigen::AngleAxisd(-0.7, Vec3(1, 3, -1).normalized()).toRotationMatrix(), Vec3(-3, 2, 8),
      Vec3(14.6, 15.3, 0), 6.5);
}

double distance_to_polygon(const Vec2& p, const std::vector<Vec2>& polygon) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec2 &a = polygon[i], &b = polygon[(i + 1) % polygon.size()];
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * (b - a) - p).norm());
  }
  return best;
}

// The normalised depth (eq. 7) the sheet has at pixel (row, col) of `image`: the restored image a
// perfect back-end would return.
cv::Mat true_depth(const testing::TiltedSheet& sheet, const RangeImage& image) {
  const Vec3 n = image.plane.frame.rotation * sheet.normal();
  const Vec3 p = image.plane.frame.to_local(sheet.shift);
  cv::Mat depth = image.depth.clone();
  for (int row = 0; row < depth.rows; ++row) {
    for (int col = 0; col < depth.cols; ++col) {
      const Vec3 local = image.local_point(row, col, 0);
      const double z = p.z() - (n.x() * (local.x() - p.x()) + n.y() * (local.y() - p.y())) / n.z();
      depth.at<float>(row, col) = static_cast<float>((z - image.depth_offset) * image.depth_scale);
    }
  }
  return depth;
}

// Checks the patch's bookkeeping: one point per listed pixel, each a hole pixel, listed in
// row-major order, `index` pointing back to it; each point is pixel (x_min + c·q, y_max − r·q) in
// the frame (eq. 13).
void expect_consistent(const RangeImage& image, const Patch& patch) {
  ASSERT_EQ(patch.points.size(), patch.pixels.size());
  ASSERT_EQ(patch.index.type(), CV_32SC1);
  ASSERT_EQ(patch.index.size(), image.labels.size());
  const cv::Mat mask = image.mask();
  int listed = 0;
  for (int row = 0; row < mask.rows; ++row) {
    for (int col = 0; col < mask.cols; ++col) {
      const int i = patch.index.at<int>(row, col);
      if (i < 0) continue;
      ASSERT_EQ(i, listed++);  // row-major
      EXPECT_EQ(patch.pixels[i], cv::Point(col, row));
      EXPECT_TRUE(mask.at<std::uint8_t>(row, col));
      const Vec3 local = image.plane.frame.to_local(patch.points[i]);
      EXPECT_NEAR(local.x(), image.x_min + col * image.step, 1e-9);
      EXPECT_NEAR(local.y(), image.y_max - row * image.step, 1e-9);
    }
  }
  EXPECT_EQ(listed, static_cast<int>(patch.points.size()));
}

// Seen along the sheet's normal, the rasterised depth (0 everywhere, the hole included) is the
// restored image of a perfect back-end: every kept hole pixel maps onto the sheet; the points
// dropped are exactly the hole pixels closer than q/2 to the projected boundary.
TEST(BackProject, FlatSheetPixelsLandOnTheSheet) {
  const testing::TiltedSheet sheet = tilted_sheet();
  Frame frame;
  frame.rotation = sheet.rotation.transpose();
  frame.origin = sheet.shift + sheet.rotation * Vec3(14, 15, 2);
  const RangeImage image =
      rasterize_zone(sheet.mesh, sheet.zone, sheet.hole,
                     hole_in_plane(sheet.mesh, sheet.hole, frame), mean_edge_length(sheet.mesh));
  const Patch patch = back_project(image, image.depth);
  expect_consistent(image, patch);
  ASSERT_GT(patch.points.size(), 60u);
  for (const Vec3& p : patch.points) EXPECT_LT(sheet.distance(p), 1e-9 * sheet.size);

  const std::vector<Vec2> polygon = hole_in_plane(sheet.mesh, sheet.hole, frame).loop;
  const double q = image.step;
  double nearest = std::numeric_limits<double>::infinity();
  int dropped = 0;
  const cv::Mat mask = image.mask();
  for (int row = 0; row < mask.rows; ++row) {
    for (int col = 0; col < mask.cols; ++col) {
      if (!mask.at<std::uint8_t>(row, col)) continue;
      const double d = distance_to_polygon(image.local_point(row, col, 0).head<2>(), polygon);
      if (patch.index.at<int>(row, col) >= 0) {
        nearest = std::min(nearest, d);
      } else {
        ++dropped;
        EXPECT_LT(d, 0.5 * q) << "pixel " << row << ", " << col << " dropped without reason";
      }
    }
  }
  EXPECT_GE(nearest, 0.5 * q);
  EXPECT_GT(dropped, 0);  // the test sees pixels near the boundary
  EXPECT_EQ(dropped + static_cast<int>(patch.points.size()), cv::countNonZero(mask));
}

// Seen at an angle, the restored depth varies; eq. 13 (with d_i and f_esc) still maps every hole
// pixel of the true depth onto the sheet (to the float precision of the normalised depth), and a
// larger clearance keeps points at least that far from the boundary.
TEST(BackProject, TiltedViewInvertsTheNormalisation) {
  const testing::TiltedSheet sheet = tilted_sheet();
  Frame frame;
  frame.rotation =
      (sheet.rotation * Eigen::AngleAxisd(0.35, Vec3(2, -1, 0).normalized()).toRotationMatrix())
          .transpose();
  frame.origin = sheet.shift + sheet.rotation * Vec3(15, 15, 0);
  const RangeImage image =
      rasterize_zone(sheet.mesh, sheet.zone, sheet.hole,
                     hole_in_plane(sheet.mesh, sheet.hole, frame), mean_edge_length(sheet.mesh));
  const double range = 1 / image.depth_scale;
  ASSERT_GT(range, 3);  // not flat in this frame
  const cv::Mat restored = true_depth(sheet, image);
  const std::vector<Vec2> polygon = hole_in_plane(sheet.mesh, sheet.hole, frame).loop;
  for (double clearance : {0.5, 2.0}) {
    BackProjectionOptions options;
    options.boundary_clearance = clearance;
    const Patch patch = back_project(image, restored, options);
    expect_consistent(image, patch);
    ASSERT_GT(patch.points.size(), 20u);
    for (const Vec3& p : patch.points) {
      EXPECT_LT(sheet.distance(p), 1e-6 * range);
      EXPECT_GE(distance_to_polygon(frame.to_local(p).head<2>(), polygon), clearance * image.step);
    }
  }
}

// Without clearance every hole pixel with a finite value is kept; NaN and infinite values are
// skipped.
TEST(BackProject, NonFiniteValuesAreSkipped) {
  const testing::TiltedSheet sheet = tilted_sheet();
  Frame frame;
  frame.rotation = sheet.rotation.transpose();
  const RangeImage image = rasterize_zone(sheet.mesh, sheet.zone, sheet.hole,
                                          hole_in_plane(sheet.mesh, sheet.hole, frame), 1.0);
  cv::Mat restored = image.depth.clone();
  std::vector<cv::Point> hole_pixels;
  cv::findNonZero(image.mask(), hole_pixels);
  ASSERT_GT(hole_pixels.size(), 100u);
  const cv::Point nan_pixel = hole_pixels[hole_pixels.size() / 2];
  const cv::Point inf_pixel = hole_pixels[hole_pixels.size() / 3];
  restored.at<float>(nan_pixel) = std::numeric_limits<float>::quiet_NaN();
  restored.at<float>(inf_pixel) = std::numeric_limits<float>::infinity();
  BackProjectionOptions options;
  options.boundary_clearance = 0;
  const Patch patch = back_project(image, restored, options);
  expect_consistent(image, patch);
  EXPECT_EQ(patch.points.size(), hole_pixels.size() - 2);
  EXPECT_EQ(patch.index.at<int>(nan_pixel), -1);
  EXPECT_EQ(patch.index.at<int>(inf_pixel), -1);
}

}  // namespace
}  // namespace rangefill
