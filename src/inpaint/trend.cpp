#include "rangefill/inpaint/trend.h"

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "rangefill/core/errors.h"

namespace rangefill {

TrendKind trend_from_name(const std::string& name) {
  if (name == "none") return TrendKind::none;
  if (name == "plane") return TrendKind::plane;
  if (name == "quadric") return TrendKind::quadric;
  if (name == "sphere") return TrendKind::sphere;
  if (name == "auto") return TrendKind::automatic;
  throw InvalidInput("unknown trend '" + name + "' (known: none, plane, quadric, sphere, auto)");
}

std::string trend_name(TrendKind kind) {
  switch (kind) {
    case TrendKind::none:
      return "none";
    case TrendKind::plane:
      return "plane";
    case TrendKind::quadric:
      return "quadric";
    case TrendKind::sphere:
      return "sphere";
    case TrendKind::automatic:
      return "auto";
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
  return at_uv((col - centre.x()) / scale, (row - centre.y()) / scale);
}

double Trend::at_uv(double u, double v) const {
  switch (kind) {
    case TrendKind::none:
    case TrendKind::automatic:
      return 0;
    case TrendKind::sphere: {
      const double du = u - sphere[0], dv = v - sphere[1];
      const double height = std::sqrt(std::max(0.0, sphere[3] * sphere[3] - du * du - dv * dv));
      return (sphere[2] + side * height) * scale / height_unit;
    }
    case TrendKind::plane:
    case TrendKind::quadric:
      return coefficients.dot(monomials(u, v));
  }
  return 0;
}

cv::Mat Trend::image(cv::Size size) const {
  cv::Mat sampled(size, CV_32F);
  for (int row = 0; row < size.height; ++row) {
    for (int col = 0; col < size.width; ++col)
      sampled.at<float>(row, col) = static_cast<float>(at(row, col));
  }
  return sampled;
}

namespace {

// The known pixels a trend is fitted to: (u, v) in the trend's units, and their values.
struct RingSamples {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> values;
};

// Least squares over `samples` of the polynomial of `kind` (plane or quadric, falling back to a
// plane, then to none); `trend` brings centre and scale.
Trend fit_polynomial(Trend trend, const RingSamples& samples, TrendKind kind) {
  for (TrendKind attempt : {kind, TrendKind::plane}) {
    const int unknowns = attempt == TrendKind::quadric ? 6 : 3;
    if (static_cast<int>(samples.values.size()) < 2 * unknowns) continue;
    Eigen::MatrixXd a(samples.values.size(), unknowns);
    Eigen::VectorXd b(samples.values.size());
    for (size_t i = 0; i < samples.values.size(); ++i) {
      a.row(i) = monomials(samples.points[i].x(), samples.points[i].y()).head(unknowns).transpose();
      b[i] = samples.values[i];
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

// Kåsa's algebraic fit, |p|² + a·p + d = 0 for p = (u, v, w), w the value in the units of u and v;
// none (kind none) when it is undetermined or leaves part of the hole outside the sphere's outline.
Trend fit_sphere(Trend trend, const RingSamples& samples, const std::vector<Eigen::Vector2d>& hole,
                 double height_unit) {
  trend.kind = TrendKind::none;
  if (samples.values.size() < 8) return trend;
  const double to_w = height_unit / trend.scale;
  Eigen::MatrixXd a(samples.values.size(), 4);
  Eigen::VectorXd b(samples.values.size());
  for (size_t i = 0; i < samples.values.size(); ++i) {
    const Eigen::Vector3d p(samples.points[i].x(), samples.points[i].y(), samples.values[i] * to_w);
    a.row(i) << p.x(), p.y(), p.z(), 1;
    b[i] = -p.squaredNorm();
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < 4) return trend;
  const Eigen::Vector4d x = qr.solve(b);
  const Eigen::Vector3d centre = -0.5 * x.head<3>();
  const double squared_radius = centre.squaredNorm() - x[3];
  if (!(squared_radius > 0) || !std::isfinite(squared_radius)) return trend;
  for (const Eigen::Vector2d& p : hole) {
    if ((p - centre.head<2>()).squaredNorm() >= squared_radius) return trend;
  }
  double side = 0;
  for (size_t i = 0; i < samples.values.size(); ++i) side += samples.values[i] * to_w - centre.z();
  trend.kind = TrendKind::sphere;
  trend.sphere << centre, std::sqrt(squared_radius);
  trend.side = side >= 0 ? 1 : -1;
  trend.height_unit = height_unit;
  return trend;
}

double squared_residual(const Trend& trend, const RingSamples& samples) {
  double sum = 0;
  for (size_t i = 0; i < samples.values.size(); ++i) {
    const double error =
        trend.at_uv(samples.points[i].x(), samples.points[i].y()) - samples.values[i];
    sum += error * error;
  }
  return sum;
}

}  // namespace

Trend fit_trend(const cv::Mat& values, const cv::Mat& labels, TrendKind kind, double ring,
                double height_unit) {
  Trend trend;
  if (kind == TrendKind::none) return trend;
  const cv::Mat hole = labels == kHolePixel;
  const int hole_pixels = cv::countNonZero(hole);
  if (hole_pixels == 0) return trend;
  const cv::Moments moments = cv::moments(hole, true);
  trend.centre = {moments.m10 / moments.m00, moments.m01 / moments.m00};
  trend.scale = std::max(1.0, std::sqrt(hole_pixels / M_PI));
  auto to_uv = [&](int row, int col) {
    return Eigen::Vector2d((col - trend.centre.x()) / trend.scale,
                           (row - trend.centre.y()) / trend.scale);
  };

  cv::Mat distance;
  cv::distanceTransform(hole == 0, distance, cv::DIST_L2, cv::DIST_MASK_5);
  RingSamples samples;
  std::vector<Eigen::Vector2d> hole_points;
  for (int row = 0; row < hole.rows; ++row) {
    for (int col = 0; col < hole.cols; ++col) {
      if (hole.at<std::uint8_t>(row, col)) hole_points.push_back(to_uv(row, col));
      if (labels.at<std::uint8_t>(row, col) != kKnownPixel || distance.at<float>(row, col) > ring) {
        continue;
      }
      samples.points.push_back(to_uv(row, col));
      samples.values.push_back(values.at<float>(row, col));
    }
  }
  const bool heights = height_unit > 0;
  if (heights && kind == TrendKind::sphere) {
    Trend sphere = fit_sphere(trend, samples, hole_points, height_unit);
    if (sphere.kind == TrendKind::sphere) return sphere;
  }
  const TrendKind polynomial = kind == TrendKind::plane ? TrendKind::plane : TrendKind::quadric;
  Trend fitted = fit_polynomial(trend, samples, polynomial);
  if (heights && kind == TrendKind::automatic && fitted.kind == TrendKind::quadric) {
    Trend sphere = fit_sphere(trend, samples, hole_points, height_unit);
    if (sphere.kind == TrendKind::sphere &&
        squared_residual(sphere, samples) < squared_residual(fitted, samples)) {
      return sphere;
    }
  }
  return fitted;
}

cv::Mat inpaint_residual(const cv::Mat& values, const cv::Mat& labels, const cv::Mat& mask,
                         const Inpainter& inpainter, TrendKind kind, double ring,
                         double height_unit, TrendKind& fitted) {
  const Trend trend = fit_trend(values, labels, kind, ring, height_unit);
  fitted = trend.kind;
  const cv::Mat trend_image = trend.image(values.size());
  cv::Mat residual = values - trend_image, restored;
  residual.setTo(0, labels == kOutsidePixel);
  inpainter.inpaint(residual, mask, restored);
  return restored + trend_image;
}

}  // namespace rangefill
