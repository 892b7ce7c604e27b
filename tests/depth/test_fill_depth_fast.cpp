// fill_depth's fast mode (DepthFillOptions::fast, fill_along_lines): planes, the occlusion rule
// and its limit, kept pixels, thread counts and the holes it leaves.
#include <cstring>

#include <gtest/gtest.h>

#include "depth_scenes.h"
#include "rangefill/depth/fill_depth.h"

namespace rangefill {
namespace {

using namespace testing::depth_scenes;

DepthFillOptions fast_options() {
  DepthFillOptions options;
  options.fast = true;
  return options;
}

// A tilted plane is linear in inverse depth along every line: discs inside it and a band along
// the image border (extrapolated along the lines that cross the band to data on one side only)
// are restored within float rounding.
TEST(FillDepthFast, RestoresATiltedPlane) {
  const Vec3 normal = Vec3(0.3, -0.4, 1).normalized();
  const cv::Mat truth = depth_image([&](const Vec3& r) { return plane_depth(r, normal, 1.8); });
  cv::Mat hole = disc({300, 200}, 15) | disc({500, 400}, 4);
  cv::Mat input = truth.clone();
  input.setTo(0, hole);
  cv::Mat filled;
  DepthFillStats stats = fill_depth(input, cv::noArray(), filled, fast_options());
  EXPECT_EQ(stats.holes, 2);
  EXPECT_EQ(stats.filled, 2);
  EXPECT_EQ(stats.filled_pixels, cv::countNonZero(hole));
  EXPECT_EQ(cv::norm(stats.filled_mask, hole, cv::NORM_INF), 0);
  EXPECT_LT(max_error(filled, truth, hole), 1e-5);

  cv::Mat band = cv::Mat::zeros(kSize, CV_8U);
  band.colRange(0, 6).setTo(255);
  input = truth.clone();
  input.setTo(0, band);
  stats = fill_depth(input, cv::noArray(), filled, fast_options());
  EXPECT_EQ(stats.filled_pixels, cv::countNonZero(band));
  // Constant along the lines into the band (one end each), so off the plane by what it changes
  // over the band's 6 columns (25 mm here).
  EXPECT_LT(max_error(filled, truth, band), 0.03);
  EXPECT_GT(max_error(filled, truth, band), 1e-3);
}

// A near plane (1 m, left of column 320) before a far one (2 m): a sensor shadow, a band on the
// far side of the edge, takes the far depth (the far plane goes on along its columns), not a ramp.
// A hole in the near plane at its silhouette, open to a wide invalid region with the far plane
// beyond, keeps the near depth: the far plane is seen only 100 pixels away (more than 4 beyond the
// near one), along the rows and a diagonal.
TEST(FillDepthFast, ShadowsTakeTheBackgroundButAFarSurfaceFarAwayDoesNot) {
  cv::Mat truth(kSize, CV_32F, cv::Scalar(2.0f));
  truth.colRange(0, 320).setTo(1.0f);
  cv::Mat shadow = cv::Mat::zeros(kSize, CV_8U);
  shadow(cv::Rect(320, 100, 12, 150)).setTo(255);
  cv::Mat input = truth.clone();
  input.setTo(0, shadow);
  cv::Mat filled;
  fill_depth(input, cv::noArray(), filled, fast_options());
  EXPECT_LT(max_error(filled, truth, shadow), 1e-5);

  input = truth.clone();
  input.colRange(320, 420).setTo(0);  // no return there, up to the far plane
  cv::Mat blob = cv::Mat::zeros(kSize, CV_8U);
  blob(cv::Rect(310, 440, 10, 40)).setTo(255);  // down to the bottom border: no interpolation
  input.setTo(0, blob);
  const DepthFillStats stats = fill_depth(input, cv::noArray(), filled, fast_options());
  EXPECT_EQ(stats.holes, 1);  // the blob is part of the invalid region
  EXPECT_LT(max_error(filled, truth, blob), 1e-5);
}

// Pixels outside the holes come back bit for bit in the input's type (16-bit here, the fill
// rounded to the millimetre and never 0), and the result is the same bits at any thread count.
TEST(FillDepthFast, KeepsOtherPixelsAndIsTheSameAtAnyThreadCount) {
  cv::Mat input = ball_before_wall_mm();
  cv::Mat hole = twelve_discs();
  hole.rowRange(0, 3).setTo(255);
  input.setTo(0, hole);
  cv::Mat one;
  const DepthFillStats on_one = fill_depth(input, cv::noArray(), one, fast_options());
  ASSERT_EQ(one.type(), CV_16UC1);
  EXPECT_EQ(on_one.filled, on_one.holes);
  EXPECT_EQ(cv::countNonZero(one == 0), 0);
  EXPECT_EQ(cv::norm(one, input, cv::NORM_INF, hole == 0), 0);
  for (int threads : {2, 3, 7}) {
    DepthFillOptions options = fast_options();
    options.threads = threads;
    cv::Mat several;
    const DepthFillStats on_several = fill_depth(input, cv::noArray(), several, options);
    EXPECT_EQ(std::memcmp(one.data, several.data, one.total() * one.elemSize()), 0) << threads;
    EXPECT_EQ(on_several.filled_pixels, on_one.filled_pixels);
  }
}

// Holes too large or on the border are left when asked, as in the default mode; pixels that see
// no valid pixel along any line in the first round are filled from the first round's fill; an
// image without a valid pixel is left whole.
TEST(FillDepthFast, LeavesHolesAsAskedAndFillsPixelsSeeingNoData) {
  cv::Mat input(kSize, CV_16U, cv::Scalar(2000));
  input(cv::Rect(0, 200, 5, 5)).setTo(0);      // on the border, 25 px
  input(cv::Rect(300, 200, 20, 20)).setTo(0);  // 400 px
  input(cv::Rect(100, 100, 3, 3)).setTo(0);    // 9 px
  DepthFillOptions options = fast_options();
  options.max_hole_pixels = 100;
  options.keep_border = true;
  cv::Mat filled;
  DepthFillStats stats = fill_depth(input, cv::noArray(), filled, options);
  EXPECT_EQ(stats.filled, 1);
  EXPECT_EQ(stats.at_border.pixels, 25);
  EXPECT_EQ(stats.too_large.pixels, 400);
  cv::Mat expected = input.clone();
  expected(cv::Rect(100, 100, 3, 3)).setTo(2000);
  EXPECT_EQ(cv::norm(filled, expected, cv::NORM_INF), 0);

  // One valid pixel, in a corner: its row, column and diagonal fill first, the rest from them.
  cv::Mat corner(kSize, CV_16U, cv::Scalar(0));
  corner.at<std::uint16_t>(0, 0) = 1234;
  stats = fill_depth(corner, cv::noArray(), filled, fast_options());
  EXPECT_EQ(stats.filled, 1);
  EXPECT_EQ(cv::countNonZero(filled != 1234), 0);

  const cv::Mat empty(kSize, CV_16U, cv::Scalar(0));
  stats = fill_depth(empty, cv::noArray(), filled, fast_options());
  EXPECT_EQ(stats.without_support.holes, 1);
  EXPECT_EQ(cv::countNonZero(stats.filled_mask), 0);
  EXPECT_EQ(cv::countNonZero(filled), 0);
}

}  // namespace
}  // namespace rangefill
