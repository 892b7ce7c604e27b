#include "rangefill/trend.h"

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "rangefill/errors.h"

namespace rangefill {

TrendKind trend_from_name(const std::string& name) {
  if (name == "none") return TrendKind::none;
  if (name == "plane") return TrendKind::plane;
  if (name == "quadric") return TrendKind::quadric;
  throw InvalidInput("unknown trend '" + name + "' (known: none, plane, quadric)");
}

std::string trend_name(TrendKind kind) {
  switch (kind) {
    case TrendKind::none:
      return "none";
    case TrendKind::plane:
      return "plane";
    case TrendKind::quadric:
      return "quadric";
  }
  return "";
}

namespace {

Eigen::Matrix<double, 6, 1> monomials(double u, double v) {
  Eigen::Matrix<double, 6, 1> m;
  m << 1, u, v, u * u, u * v, v * v;
  return m;
}

}  // namespace

double Trend::at(int row, int col) const {
  if (kind == TrendKind::none) return 0;
  return coefficients.dot(monomials((col - centre.x()) / scale, (row - centre.y()) / scale));
}

cv::Mat Trend::image(cv::Size size) const {
  cv::Mat sampled(size, CV_32F);
  for (int row = 0; row < size.height; ++row) {
    for (int col = 0; col < size.width; ++col)
      sampled.at<float>(row, col) = static_cast<float>(at(row, col));
  }
  return sampled;
}

Trend fit_trend(const RangeImage& image, TrendKind kind, double ring) {
  return fit_trend(image.depth, image.labels, kind, ring);
}

Trend fit_trend(const cv::Mat& values, const cv::Mat& labels, TrendKind kind, double ring) {
  Trend trend;
  if (kind == TrendKind::none) return trend;
  const cv::Mat hole = labels == kHolePixel;
  const int hole_pixels = cv::countNonZero(hole);
  if (hole_pixels == 0) return trend;
  const cv::Moments moments = cv::moments(hole, true);
  trend.centre = {moments.m10 / moments.m00, moments.m01 / moments.m00};
  trend.scale = std::max(1.0, std::sqrt(hole_pixels / M_PI));

  cv::Mat distance;
  cv::distanceTransform(hole == 0, distance, cv::DIST_L2, cv::DIST_MASK_5);
  std::vector<Eigen::Matrix<double, 6, 1>> rows;
  std::vector<double> known;
  for (int row = 0; row < hole.rows; ++row) {
    for (int col = 0; col < hole.cols; ++col) {
      if (labels.at<std::uint8_t>(row, col) != kKnownPixel || distance.at<float>(row, col) > ring) {
        continue;
      }
      rows.push_back(monomials((col - trend.centre.x()) / trend.scale,
                               (row - trend.centre.y()) / trend.scale));
      known.push_back(values.at<float>(row, col));
    }
  }
  for (TrendKind attempt : {kind, TrendKind::plane}) {
    const int unknowns = attempt == TrendKind::quadric ? 6 : 3;
    if (static_cast<int>(known.size()) < 2 * unknowns) continue;
    Eigen::MatrixXd a(known.size(), unknowns);
    Eigen::VectorXd b(known.size());
    for (size_t i = 0; i < known.size(); ++i) {
      a.row(i) = rows[i].head(unknowns).transpose();
      b[i] = known[i];
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
    if (qr.rank() < unknowns) continue;
    trend.kind = attempt;
    trend.coefficients.setZero();
    trend.coefficients.head(unknowns) = qr.solve(b);
    return trend;
  }
  return trend;
}

}  // namespace rangefill
