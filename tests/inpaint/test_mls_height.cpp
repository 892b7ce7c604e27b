// The "mls" back-end (inpaint/mls_height.h): Wang & Oliveira's moving-least-squares height fit,
// checked against eq. 7 solved directly, on quadratics it must reproduce, and on the fallbacks.
#include "rangefill/inpaint/mls_height.h"

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "rangefill/core/errors.h"

namespace rangefill {
namespace {

// 255 inside the ellipse of semi-axes a, b (pixels) turned by `degrees` about `centre`.
void draw_ellipse(cv::Mat& mask, cv::Point centre, double a, double b, double degrees = 0) {
  const double c = std::cos(degrees * M_PI / 180), s = std::sin(degrees * M_PI / 180);
  for (int row = 0; row < mask.rows; ++row) {
    for (int col = 0; col < mask.cols; ++col) {
      const double x = col - centre.x, y = row - centre.y;
      const double u = (c * x + s * y) / a, v = (-s * x + c * y) / b;
      if (u * u + v * v <= 1) mask.at<std::uint8_t>(row, col) = 255;
    }
  }
}

cv::Mat image_of(cv::Size size, double (*f)(double row, double col)) {
  cv::Mat image(size, CV_32F);
  for (int row = 0; row < size.height; ++row) {
    for (int col = 0; col < size.width; ++col) image.at<float>(row, col) = float(f(row, col));
  }
  return image;
}

double quadratic(double row, double col) {
  return 0.3 + 0.01 * col - 0.02 * row + 4e-4 * col * col - 3e-4 * row * row + 5e-4 * row * col;
}

// Largest |out − expected| over the masked pixels.
double max_error(const cv::Mat& out, const cv::Mat& expected, const cv::Mat& mask) {
  cv::Mat difference = cv::abs(out - expected);
  double worst = 0;
  cv::minMaxLoc(difference, nullptr, &worst, nullptr, nullptr, mask);
  return worst;
}

// max_error of the fill at α of `depth`'s masked pixels.
double max_error_at(double alpha, const cv::Mat& depth, const cv::Mat& mask) {
  MlsHeightOptions options;
  options.alpha = alpha;
  cv::Mat out;
  MlsHeightInpainter(options).inpaint(depth, mask, out);
  return max_error(out, depth, mask);
}

// Eq. 7 for one pixel p, solved as written: a(p) = (B·W(p)·Bᵀ)⁻¹·B·W(p)·f over the ring pixels,
// with W(p) = diag(exp(−α·d_i²) / d_i²) (eq. 6) and B the columns (1, u, v, u², v², uv) (eq. 4).
double eq7(const std::vector<cv::Point>& ring, const cv::Mat& depth, cv::Point p, double alpha) {
  const int n = static_cast<int>(ring.size());
  Eigen::MatrixXd b(6, n);
  Eigen::VectorXd w(n), f(n);
  // (u, v) about the middle of the image, in units of 10 pixels: the fit does not depend on the
  // frame, its conditioning does.
  auto frame = [](cv::Point q) { return Eigen::Vector2d((q.x - 15) / 10.0, (q.y - 14) / 10.0); };
  for (int i = 0; i < n; ++i) {
    const double u = frame(ring[i]).x(), v = frame(ring[i]).y();
    b.col(i) << 1, u, v, u * u, v * v, u * v;
    const double d2 = std::pow(ring[i].x - p.x, 2) + std::pow(ring[i].y - p.y, 2);
    w[i] = std::exp(-alpha * d2) / d2;
    f[i] = depth.at<float>(ring[i]);
  }
  const Eigen::VectorXd a =
      (b * w.asDiagonal() * b.transpose()).ldlt().solve(b * w.asDiagonal() * f);
  const double u = frame(p).x(), v = frame(p).y();
  return a.dot((Eigen::VectorXd(6) << 1, u, v, u * u, v * v, u * v).finished());
}

// The fill equals eq. 7 solved per pixel over the known pixels within `ring` pixels of the hole.
TEST(MlsHeight, EveryPixelSolvesEquation7) {
  cv::Mat depth(28, 31, CV_32F);
  cv::RNG random(7);
  random.fill(depth, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::Mat mask = cv::Mat::zeros(depth.size(), CV_8U);
  draw_ellipse(mask, {15, 13}, 7, 5, 30);
  MlsHeightOptions options;
  options.alpha = 0.05;
  options.ring = 3;
  cv::Mat out;
  MlsHeightInpainter(options).inpaint(depth, mask, out);

  std::vector<cv::Point> ring;  // the known pixels within 3 pixels of a masked one
  for (int row = 0; row < depth.rows; ++row) {
    for (int col = 0; col < depth.cols; ++col) {
      bool near = false;
      for (int r = row - 3; r <= row + 3; ++r) {
        for (int c = col - 3; c <= col + 3; ++c) {
          near |= r >= 0 && r < depth.rows && c >= 0 && c < depth.cols &&
                  mask.at<std::uint8_t>(r, c) && (r - row) * (r - row) + (c - col) * (c - col) <= 9;
        }
      }
      if (!mask.at<std::uint8_t>(row, col) && near) ring.emplace_back(col, row);
    }
  }
  ASSERT_GT(ring.size(), 60u);
  int checked = 0;
  for (int row = 0; row < depth.rows; ++row) {
    for (int col = 0; col < depth.cols; ++col) {
      if (!mask.at<std::uint8_t>(row, col)) continue;
      EXPECT_NEAR(out.at<float>(row, col), eq7(ring, depth, {col, row}, 0.05), 1e-5)
          << row << ", " << col;
      ++checked;
    }
  }
  EXPECT_GT(checked, 80);
}

// A quadratic height field comes back exactly, whatever the shape of the holes, at the α the
// weights stay spread for (a steep α leaves far pixels with the nearest few ring pixels alone).
TEST(MlsHeight, ReproducesQuadratics) {
  const cv::Mat depth = image_of({64, 48}, quadratic);
  cv::Mat mask = cv::Mat::zeros(depth.size(), CV_8U);
  draw_ellipse(mask, {20, 30}, 12, 12);
  mask(cv::Rect(5, 3, 30, 4)).setTo(255);
  for (double alpha : {0.0, 1.0 / 64, 1.0 / 16}) {
    EXPECT_LT(max_error_at(alpha, depth, mask), 2e-6) << "alpha " << alpha;
  }
}

// Far from the ring exp(−α·d²) underflows to 0; the weights are then rescaled: the fill stays
// finite, within the known values, and exact on a constant.
TEST(MlsHeight, LargeHolesWithSteepWeightsDoNotUnderflow) {
  cv::Mat mask = cv::Mat::zeros(60, 60, CV_8U);
  draw_ellipse(mask, {30, 30}, 20, 20);
  MlsHeightOptions options;
  options.alpha = 4;  // exp(−4·20²) = 0 in double
  const cv::Mat constant(mask.size(), CV_32F, cv::Scalar(0.37));
  cv::Mat out;
  MlsHeightInpainter(options).inpaint(constant, mask, out);
  EXPECT_LT(max_error(out, constant, mask), 1e-6);
  const cv::Mat plane =
      image_of(mask.size(), [](double row, double col) { return 0.2 + 0.005 * row + 0.003 * col; });
  MlsHeightInpainter(options).inpaint(plane, mask, out);
  double lowest = 0, highest = 0;
  cv::minMaxLoc(out, &lowest, &highest, nullptr, nullptr, mask);
  EXPECT_GE(lowest, 0.2);
  EXPECT_LE(highest, 0.2 + 0.005 * 59 + 0.003 * 59);
}

// Known pixels only in two columns: the quadratic's u² is not determined and the fit falls back to
// the plane, which restores a plane exactly.
TEST(MlsHeight, IllConditionedFitsFallBackToAPlane) {
  const cv::Mat depth =
      image_of({20, 20}, [](double row, double col) { return 0.5 + 0.01 * row - 0.02 * col; });
  cv::Mat mask(depth.size(), CV_8U, cv::Scalar(255));
  mask.col(0).setTo(0);
  mask.col(19).setTo(0);
  cv::Mat out;
  MlsHeightInpainter().inpaint(depth, mask, out);
  EXPECT_LT(max_error(out, depth, mask), 1e-5);
}

// Each hole is fitted from its own ring: two holes on two levels of a step, each further than the
// ring from the step, come back at their own level exactly.
TEST(MlsHeight, EachHoleUsesItsOwnRing) {
  const cv::Mat depth =
      image_of({30, 60}, [](double, double col) { return col < 30 ? 0.25 : 0.75; });
  cv::Mat mask = cv::Mat::zeros(depth.size(), CV_8U);
  draw_ellipse(mask, {12, 15}, 6, 6);
  draw_ellipse(mask, {47, 15}, 6, 6);
  for (double alpha : {0.0, 1.0 / 16}) {
    EXPECT_LT(max_error_at(alpha, depth, mask), 1e-6) << "alpha " << alpha;
  }
}

TEST(MlsHeight, RefusesBadOptions) {
  MlsHeightOptions options;
  options.alpha = -0.1;
  EXPECT_THROW(MlsHeightInpainter{options}, InvalidInput);
  options.alpha = std::nan("");
  EXPECT_THROW(MlsHeightInpainter{options}, InvalidInput);
  options = {};
  options.ring = 0.5;
  EXPECT_THROW(MlsHeightInpainter{options}, InvalidInput);
}

}  // namespace
}  // namespace rangefill
