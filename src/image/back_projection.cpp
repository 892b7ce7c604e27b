#include "rangefill/image/back_projection.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace rangefill {

Patch back_project(const RangeImage& image, const cv::Mat& restored,
                   const BackProjectionOptions& options) {
  const std::vector<Vec2>& polygon = image.plane.loop;
  const cv::Mat mask = image.mask();
  // Pixels deeper than a few pixels inside the mask cannot be near the boundary: test only the rim.
  cv::Mat depth_in_mask;
  cv::distanceTransform(mask, depth_in_mask, cv::DIST_L2, cv::DIST_MASK_3);
  const double clearance = options.boundary_clearance * image.step;
  const double rim = options.boundary_clearance + 2.0;

  Patch patch;
  patch.index = cv::Mat(mask.size(), CV_32S, cv::Scalar(-1));
  for (int row = 0; row < mask.rows; ++row) {
    for (int col = 0; col < mask.cols; ++col) {
      if (!mask.at<std::uint8_t>(row, col)) continue;
      const float value = restored.at<float>(row, col);
      if (!std::isfinite(value)) continue;
      const Vec3 local = image.local_point(row, col, value);
      if (depth_in_mask.at<float>(row, col) <= rim) {
        bool too_close = false;
        for (size_t i = 0; i < polygon.size() && !too_close; ++i) {
          too_close = distance_to_segment(local.head<2>(), polygon[i],
                                          polygon[(i + 1) % polygon.size()]) < clearance;
        }
        if (too_close) continue;
      }
      patch.index.at<int>(row, col) = static_cast<int>(patch.points.size());
      patch.points.push_back(image.plane.frame.to_world(local));
      patch.pixels.emplace_back(col, row);
    }
  }
  return patch;
}

std::vector<Rgb> patch_colors(const Patch& patch, const cv::Mat& restored_color) {
  std::vector<Rgb> colors;
  colors.reserve(patch.pixels.size());
  for (const cv::Point& pixel : patch.pixels) {
    const cv::Vec3f& rgb = restored_color.at<cv::Vec3f>(pixel);
    colors.push_back(Rgb(rgb[0], rgb[1], rgb[2]).cwiseMax(0.0f).cwiseMin(1.0f));
  }
  return colors;
}

}  // namespace rangefill
