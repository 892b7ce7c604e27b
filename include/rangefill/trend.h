// An optional step between the range image and the inpainter: a low-order surface fitted to the
// known pixels around the hole is subtracted before inpainting and added back after, so that the
// back-end restores only what the surface does beyond its local trend. Not in the Pérez paper; see
// RepairOptions::trend for why it is on by default and how to switch it off for ablations.
#pragma once

#include <string>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "rangefill/range_image.h"

namespace rangefill {

enum class TrendKind { none, plane, quadric };

/// "none", "plane", "quadric"; throws InvalidInput otherwise.
TrendKind trend_from_name(const std::string& name);
std::string trend_name(TrendKind kind);

/// t(c, r) = a0 + a1·u + a2·v [+ a3·u² + a4·u·v + a5·v²], u, v the column and row relative to the
/// hole's centre in units of the hole's radius (a well-conditioned fit at any image size).
struct Trend {
  TrendKind kind = TrendKind::none;
  Eigen::Matrix<double, 6, 1> coefficients = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // (column, row)
  double scale = 1;                                  // pixels per unit of u, v

  double at(int row, int col) const;
  /// The trend sampled on a CV_32F image of `size`.
  cv::Mat image(cv::Size size) const;
};

/// Least-squares fit to the known pixels within `ring` pixels of the hole mask. Falls back to a
/// plane, then to none, when the pixels do not determine the surface (fewer than twice the
/// unknowns, or a rank-deficient system).
Trend fit_trend(const RangeImage& image, TrendKind kind, double ring = 6);

/// The same fit to any CV_32F image `values` over the pixels of a range image's `labels` (a colour
/// channel of RangeImage::color, for instance).
Trend fit_trend(const cv::Mat& values, const cv::Mat& labels, TrendKind kind, double ring = 6);

}  // namespace rangefill
