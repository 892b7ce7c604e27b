// An optional step before the inpainter: a low-order surface fitted to the known pixels around the
// hole is subtracted before inpainting and added back after, so that the back-end restores only
// what the surface does beyond its local trend. Used by the image pipeline (image/plane_filler.h,
// PlaneFillerOptions::trend says why it is on by default and how to switch it off for ablations)
// and by depth filling (depth/fill_depth.h). Not in the Pérez paper.
#pragma once

#include <string>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "rangefill/inpaint/inpainter.h"
#include "rangefill/inpaint/pixel_labels.h"

namespace rangefill {

/// sphere: a sphere fitted to the height field (its values in pixel units, see fit_trend), what
/// a quadric cannot continue: a sphere's height curves faster towards its rim, so a quadric fitted
/// around a wide cap's hole overshoots the sphere inside it.
/// automatic ("auto"): the sphere where it fits the known pixels around the hole more closely than
/// the quadric (with two parameters fewer), else the quadric.
enum class TrendKind { none, plane, quadric, sphere, automatic };

/// "none", "plane", "quadric", "sphere", "auto"; throws InvalidInput otherwise.
TrendKind trend_from_name(const std::string& name);
std::string trend_name(TrendKind kind);

/// t(c, r) = a0 + a1·u + a2·v [+ a3·u² + a4·u·v + a5·v²], u, v the column and row relative to the
/// hole's centre in units of the hole's radius (a well-conditioned fit at any image size); for a
/// sphere of centre (u0, v0, w0) and radius R in those units, t = (w0 ± √(R² − (u − u0)² −
/// (v − v0)²)) · scale / height_unit, the side the known pixels lie on.
struct Trend {
  TrendKind kind = TrendKind::none;  // never automatic: the kind chosen
  Eigen::Matrix<double, 6, 1> coefficients = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Vector4d sphere = Eigen::Vector4d::Zero();  // u0, v0, w0, R
  double side = 1;                                   // +1: the cap above the centre, −1 below
  double height_unit = 0;                            // pixels per unit of value (sphere)
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // (column, row)
  double scale = 1;                                  // pixels per unit of u, v

  double at(int row, int col) const;
  /// The same at (u, v).
  double at_uv(double u, double v) const;
  /// The trend sampled on a CV_32F image of `size`.
  cv::Mat image(cv::Size size) const;
};

/// Least-squares fit to the CV_32F `values` at the known pixels (PixelLabel `labels`) within
/// `ring` pixels of the hole pixels (the sphere: the algebraic fit of Kåsa, then the height on the
/// known pixels' side). Falls back from a sphere to the quadric when the fitted sphere does not
/// cover the hole, and to a plane, then to none, when the pixels do not determine the surface
/// (fewer than twice the unknowns, or a rank-deficient system). `height_unit` is the pixels per
/// unit of value, 0 for values that are not heights (a colour channel; then sphere and automatic
/// fit the quadric).
Trend fit_trend(const cv::Mat& values, const cv::Mat& labels, TrendKind kind, double ring = 6,
                double height_unit = 0);

/// The trend of `values` (fit_trend over the known pixels of `labels`) removed, the residual
/// restored by `inpainter` under `mask`, the trend added back. Outside the zone (kOutsidePixel)
/// the image holds the nearest zone value, no surface: there the residual is 0 (the trend is the
/// best guess), else back-ends that read beyond the rim (mls) take the gap between a flat extension
/// and a curved trend for surface. `fitted` receives the trend actually fitted.
cv::Mat inpaint_residual(const cv::Mat& values, const cv::Mat& labels, const cv::Mat& mask,
                         const Inpainter& inpainter, TrendKind kind, double ring,
                         double height_unit, TrendKind& fitted);

}  // namespace rangefill
