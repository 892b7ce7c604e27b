// The trend step (trend.h): a plane or quadric fitted to the known pixels around the hole, its
// fallbacks when the pixels do not determine it, and the names.
#include "rangefill/inpaint/trend.h"

#include <cmath>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "rangefill/image/range_image.h"

namespace rangefill {
namespace {

constexpr int kRows = 41, kCols = 51;

// A 41×51 range image whose pixels are known with depth `surface(row, col)`, except a disk of
// hole pixels of radius 6 around (row 20, column 25).
template <typename Surface>
RangeImage image_with_disk(Surface surface) {
  RangeImage image;
  image.depth = cv::Mat(kRows, kCols, CV_32F);
  image.labels = cv::Mat(kRows, kCols, CV_8U, cv::Scalar(kKnownPixel));
  image.step = 1;
  for (int row = 0; row < kRows; ++row) {
    for (int col = 0; col < kCols; ++col) {
      const bool hole = (row - 20) * (row - 20) + (col - 25) * (col - 25) <= 36;
      image.labels.at<std::uint8_t>(row, col) = hole ? kHolePixel : kKnownPixel;
      image.depth.at<float>(row, col) = hole ? 0.0f : static_cast<float>(surface(row, col));
    }
  }
  return image;
}

// Dyadic coefficients: every value is exact in float, so a fit can be exact.
double quadric(int row, int col) {
  return 2 + 0.5 * col - 0.25 * row + 0.0625 * col * col - 0.03125 * row * col +
         0.015625 * row * row;
}
double plane(int row, int col) {
  return -1.5 + 0.125 * col + 0.375 * row;
}

// Largest |trend.at − surface| over the whole image, hole included.
template <typename Surface>
double worst_error(const Trend& trend, Surface surface) {
  double worst = 0;
  for (int row = 0; row < kRows; ++row) {
    for (int col = 0; col < kCols; ++col)
      worst = std::max(worst, std::abs(trend.at(row, col) - surface(row, col)));
  }
  return worst;
}

// A quadric is recovered exactly (to rounding) from the ring of known pixels, inside the hole as
// well; centre and scale are the hole's centroid and radius sqrt(pixels / π).
TEST(FitTrend, RecoversAQuadricExactly) {
  const RangeImage image = image_with_disk(quadric);
  const Trend trend = fit_trend(image, TrendKind::quadric);
  EXPECT_EQ(trend.kind, TrendKind::quadric);
  const int hole_pixels = cv::countNonZero(image.mask());
  EXPECT_EQ(hole_pixels, 113);  // lattice points in a disk of radius 6
  EXPECT_NEAR(trend.centre.x(), 25, 1e-12);
  EXPECT_NEAR(trend.centre.y(), 20, 1e-12);
  EXPECT_NEAR(trend.scale, std::sqrt(113 / M_PI), 1e-12);
  EXPECT_LT(worst_error(trend, quadric), 1e-9);  // values up to 170
  // image() samples at() as floats.
  const cv::Mat sampled = trend.image(image.depth.size());
  ASSERT_EQ(sampled.type(), CV_32FC1);
  ASSERT_EQ(sampled.size(), image.depth.size());
  for (int row = 0; row < kRows; row += 5) {
    for (int col = 0; col < kCols; col += 5)
      EXPECT_EQ(sampled.at<float>(row, col), static_cast<float>(trend.at(row, col)));
  }
  // A plane cannot follow it: the residual of the plane fit is large.
  EXPECT_GT(worst_error(fit_trend(image, TrendKind::plane), quadric), 1);
}

// A plane is recovered exactly by both fits; the plane fit leaves the quadratic terms zero.
TEST(FitTrend, RecoversAPlaneExactly) {
  const RangeImage image = image_with_disk(plane);
  const Trend flat = fit_trend(image, TrendKind::plane);
  EXPECT_EQ(flat.kind, TrendKind::plane);
  EXPECT_LT(worst_error(flat, plane), 1e-10);
  EXPECT_EQ(flat.coefficients.tail<3>(), Eigen::Vector3d::Zero());
  const Trend curved = fit_trend(image, TrendKind::quadric);
  EXPECT_EQ(curved.kind, TrendKind::quadric);
  EXPECT_LT(worst_error(curved, plane), 1e-9);
  EXPECT_LT(curved.coefficients.tail<3>().norm(), 1e-9);
}

// A sphere of radius 40 pixels (heights in pixels: step and depth scale 1) seen from above.
double sphere(int row, int col) {
  return -20 + std::sqrt(1600.0 - (row - 18) * (row - 18) - (col - 27) * (col - 27));
}

// The sphere trend recovers a sphere's height field from the ring, inside the hole as well (to the
// float rounding of the values); the automatic trend takes it over the quadric there, and the
// quadric over the sphere on a quadric's height field.
TEST(FitTrend, RecoversASphereAndChoosesItOnlyOnASphere) {
  const RangeImage cap = image_with_disk(sphere);
  const Trend fitted = fit_trend(cap, TrendKind::sphere, 3);
  ASSERT_EQ(fitted.kind, TrendKind::sphere);
  EXPECT_NEAR(fitted.sphere[3] * fitted.scale, 40, 1e-3);
  EXPECT_EQ(fitted.side, 1);
  EXPECT_LT(worst_error(fitted, sphere), 1e-3);
  EXPECT_GT(worst_error(fit_trend(cap, TrendKind::quadric, 3), sphere), 10 * 1e-3);
  EXPECT_EQ(fit_trend(cap, TrendKind::automatic, 3).kind, TrendKind::sphere);
  EXPECT_EQ(fit_trend(image_with_disk(quadric), TrendKind::automatic, 3).kind, TrendKind::quadric);
  // Values that are not heights (height_unit 0, a colour channel) get the quadric.
  EXPECT_EQ(fit_trend(cap.depth, cap.labels, TrendKind::automatic, 3).kind, TrendKind::quadric);
  for (TrendKind kind : {TrendKind::sphere, TrendKind::automatic})
    EXPECT_EQ(trend_from_name(trend_name(kind)), kind);
}

// Only known pixels within `ring` pixels of the mask are fitted: a quadric outside the ring does
// not disturb a plane inside it (ring 3: pixels at distance > 3 follow another surface).
TEST(FitTrend, FitsOnlyTheRingAroundTheHole) {
  RangeImage image = image_with_disk(plane);
  for (int row = 0; row < kRows; ++row) {
    for (int col = 0; col < kCols; ++col) {
      const double distance = std::hypot(row - 20, col - 25);
      if (distance > 10) image.depth.at<float>(row, col) = static_cast<float>(quadric(row, col));
    }
  }
  const Trend trend = fit_trend(image, TrendKind::quadric, 3);
  EXPECT_EQ(trend.kind, TrendKind::quadric);
  EXPECT_LT(worst_error(trend, plane), 1e-9);
}

// An image with only the hole and the listed known pixels (the rest outside the zone).
RangeImage sparse_image(const std::vector<std::pair<int, int>>& known) {
  RangeImage image = image_with_disk(quadric);
  for (int row = 0; row < kRows; ++row) {
    for (int col = 0; col < kCols; ++col) {
      if (image.labels.at<std::uint8_t>(row, col) == kKnownPixel)
        image.labels.at<std::uint8_t>(row, col) = kOutsidePixel;
    }
  }
  for (auto [row, col] : known) image.labels.at<std::uint8_t>(row, col) = kKnownPixel;
  return image;
}

// Fewer than twice the unknowns: 8 known pixels (< 12) give a plane instead of a quadric, 5 (< 6)
// give none. A rank-deficient system falls back too: pixels on one row determine neither a
// quadric nor a plane; on two rows, a plane but not a quadric (v² is affine in v there).
TEST(FitTrend, FallsBackWhenThePixelsDoNotDetermineTheSurface) {
  // Around the disk (radius 6 about (20, 25)), within 3 pixels of it.
  const std::vector<std::pair<int, int>> eight = {{13, 25}, {27, 25}, {20, 18}, {20, 32},
                                                  {15, 21}, {15, 29}, {25, 21}, {25, 29}};
  const Trend plane_only = fit_trend(sparse_image(eight), TrendKind::quadric);
  EXPECT_EQ(plane_only.kind, TrendKind::plane);
  EXPECT_EQ(plane_only.coefficients.tail<3>(), Eigen::Vector3d::Zero());
  // The plane through those pixels: exact on them up to least squares (they lie on a quadric).
  EXPECT_NE(plane_only.coefficients.head<3>(), Eigen::Vector3d::Zero());

  const std::vector<std::pair<int, int>> five(eight.begin(), eight.begin() + 5);
  const Trend none = fit_trend(sparse_image(five), TrendKind::quadric);
  EXPECT_EQ(none.kind, TrendKind::none);
  EXPECT_EQ(none.coefficients, (Eigen::Matrix<double, 6, 1>::Zero()));
  EXPECT_EQ(none.at(20, 25), 0);
  EXPECT_EQ(fit_trend(sparse_image(five), TrendKind::plane).kind, TrendKind::none);

  std::vector<std::pair<int, int>> one_row, two_rows;
  for (int col = 15; col <= 35; ++col) {
    one_row.emplace_back(13, col);
    two_rows.emplace_back(13, col);
    two_rows.emplace_back(27, col);
  }
  EXPECT_EQ(fit_trend(sparse_image(one_row), TrendKind::quadric).kind, TrendKind::none);
  EXPECT_EQ(fit_trend(sparse_image(two_rows), TrendKind::quadric).kind, TrendKind::plane);
}

// `none` fits nothing; neither does an image without hole pixels.
TEST(FitTrend, NoneAndNoHoleGiveNoTrend) {
  const RangeImage image = image_with_disk(quadric);
  const Trend none = fit_trend(image, TrendKind::none);
  EXPECT_EQ(none.kind, TrendKind::none);
  EXPECT_EQ(none.at(3, 4), 0);
  EXPECT_EQ(cv::countNonZero(none.image({7, 5})), 0);
  RangeImage full = image;
  full.labels = cv::Mat(kRows, kCols, CV_8U, cv::Scalar(kKnownPixel));
  EXPECT_EQ(fit_trend(full, TrendKind::quadric).kind, TrendKind::none);
}

// Names round-trip; anything else throws InvalidInput naming the known ones.
TEST(TrendNames, RoundTripAndUnknownThrows) {
  for (TrendKind kind : {TrendKind::none, TrendKind::plane, TrendKind::quadric})
    EXPECT_EQ(trend_from_name(trend_name(kind)), kind);
  EXPECT_EQ(trend_name(TrendKind::none), "none");
  EXPECT_EQ(trend_name(TrendKind::plane), "plane");
  EXPECT_EQ(trend_name(TrendKind::quadric), "quadric");
  EXPECT_EQ(trend_from_name("quadric"), TrendKind::quadric);
  EXPECT_THROW(trend_from_name("cubic"), InvalidInput);
  EXPECT_THROW(trend_from_name("Plane"), InvalidInput);
  try {
    trend_from_name("cubic");
  } catch (const InvalidInput& error) {
    EXPECT_NE(std::string(error.what()).find("none, plane, quadric"), std::string::npos);
  }
}

}  // namespace
}  // namespace rangefill
