// Depth scenes for the depth tests: a PrimeSense-like camera, planes and spheres seen along its
// rays, discs of pixels.
#pragma once

#include <cmath>
#include <functional>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "rangefill/core/mesh.h"
#include "rangefill/core/render.h"

namespace rangefill::testing::depth_scenes {

inline const CameraIntrinsics kCamera;  // 525, 525, 319.5, 239.5
inline const cv::Size kSize(640, 480);

// The direction (z = 1) of the ray through pixel (col, row).
inline Vec3 ray(int col, int row) {
  return {(col - kCamera.cx) / kCamera.fx, (row - kCamera.cy) / kCamera.fy, 1};
}

// CV_32F metres: depth(ray) at every pixel.
inline cv::Mat depth_image(const std::function<double(const Vec3&)>& depth) {
  cv::Mat image(kSize, CV_32F);
  for (int row = 0; row < kSize.height; ++row) {
    for (int col = 0; col < kSize.width; ++col)
      image.at<float>(row, col) = static_cast<float>(depth(ray(col, row)));
  }
  return image;
}

// The plane n·X = d seen along a ray.
inline double plane_depth(const Vec3& direction, const Vec3& normal, double d) {
  return d / normal.dot(direction);
}

// The sphere |X − centre| = radius seen along a ray (its near side), 0 where missed.
inline double sphere_depth(const Vec3& direction, const Vec3& centre, double radius) {
  const double a = direction.squaredNorm(), b = direction.dot(centre);
  const double discriminant = b * b - a * (centre.squaredNorm() - radius * radius);
  return discriminant < 0 ? 0 : (b - std::sqrt(discriminant)) / a;
}

inline cv::Mat disc(cv::Point centre, int radius) {
  cv::Mat mask = cv::Mat::zeros(kSize, CV_8U);
  cv::circle(mask, centre, radius, cv::Scalar(255), cv::FILLED);
  return mask;
}

// A ball (radius 0.5 m, centre 2 m ahead) before a wall 3 m away, CV_16U millimetres.
inline cv::Mat ball_before_wall_mm() {
  cv::Mat depth;
  depth_image([](const Vec3& r) {
    const double ball = sphere_depth(r, {0, 0, 2}, 0.5);
    return ball > 0 ? ball : plane_depth(r, {0, 0, 1}, 3);
  }).convertTo(depth, CV_16U, 1000);
  return depth;
}

// Twelve discs of 3 to 6 pixels in a row across ball_before_wall_mm(), some at its silhouette.
inline cv::Mat twelve_discs() {
  cv::Mat mask = cv::Mat::zeros(kSize, CV_8U);
  for (int k = 0; k < 12; ++k) mask |= disc({60 + 45 * k, 120 + 20 * (k % 5)}, 3 + k % 4);
  return mask;
}

// Largest |a − b| (metres) over the mask.
inline double max_error(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask) {
  cv::Mat a64, b64;
  a.convertTo(a64, CV_64F);
  b.convertTo(b64, CV_64F);
  return cv::norm(a64, b64, cv::NORM_INF, mask);
}

}  // namespace rangefill::testing::depth_scenes
