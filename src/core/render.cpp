#include "rangefill/core/render.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "rangefill/core/errors.h"

namespace rangefill {

Eigen::Isometry3d look_at(const Vec3& eye, const Vec3& target, const Vec3& up) {
  const Vec3 forward = (target - eye).normalized();
  const Vec3 right = forward.cross(up);
  if (!((target - eye).norm() > 0) || !(right.norm() > 1e-12 * up.norm())) {
    throw InvalidInput("look_at: the view direction is undefined or parallel to up");
  }
  Eigen::Matrix3d rotation;  // rows: the camera's x (right), y (down), z (forward) in the world
  rotation.row(0) = right.normalized();
  rotation.row(2) = forward;
  rotation.row(1) = forward.cross(rotation.row(0).transpose());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  pose.translation() = -rotation * eye;
  return pose;
}

namespace {

// Z-buffers a triangle given by camera-space corners in front of the camera (z > 0): pixel centres
// inside it (either orientation, edges included), 1/z interpolated linearly in the image.
void rasterize(const std::array<Vec3, 3>& corners, const CameraIntrinsics& camera,
               cv::Mat_<float>& depth) {
  std::array<Vec3, 3> image;  // (u, v, 1/z)
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = corners[k];
    image[k] = {camera.fx * p.x() / p.z() + camera.cx, camera.fy * p.y() / p.z() + camera.cy,
                1 / p.z()};
  }
  const Vec3 &a = image[0], &b = image[1], &c = image[2];
  const double area2 = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  if (area2 == 0) return;  // seen edge-on
  // The pixel range of the bounding box, clamped before any conversion (corners near the camera
  // project far outside the image).
  const auto first = [](double lowest, int size) {
    return static_cast<int>(std::clamp(std::ceil(lowest), 0.0, static_cast<double>(size)));
  };
  const auto last = [](double highest, int size) {
    return static_cast<int>(std::clamp(std::floor(highest), -1.0, size - 1.0));
  };
  const int col_begin = first(std::min({a.x(), b.x(), c.x()}), depth.cols);
  const int col_end = last(std::max({a.x(), b.x(), c.x()}), depth.cols);
  const int row_begin = first(std::min({a.y(), b.y(), c.y()}), depth.rows);
  const int row_end = last(std::max({a.y(), b.y(), c.y()}), depth.rows);
  for (int row = row_begin; row <= row_end; ++row) {
    for (int col = col_begin; col <= col_end; ++col) {
      double inverse_z = 0;
      bool inside = true;
      for (int k = 0; k < 3 && inside; ++k) {
        const Vec3& p = image[(k + 1) % 3];
        const Vec3& q = image[(k + 2) % 3];
        const double weight =
            ((q.x() - p.x()) * (row - p.y()) - (q.y() - p.y()) * (col - p.x())) / area2;
        inside = weight >= -1e-9;
        inverse_z += weight * image[k].z();
      }
      if (!inside) continue;
      const float z = static_cast<float>(1 / inverse_z);
      float& pixel = depth(row, col);
      if (pixel == 0 || z < pixel) pixel = z;
    }
  }
}

}  // namespace

cv::Mat render_depth(const Mesh& mesh, const CameraIntrinsics& camera,
                     const Eigen::Isometry3d& world_to_camera, cv::Size size, double near) {
  std::vector<Vec3> local(mesh.positions.size());
  for (size_t i = 0; i < local.size(); ++i) local[i] = world_to_camera * mesh.positions[i];
  cv::Mat_<float> depth(size, 0.0f);
  for (const Triangle& triangle : mesh.triangles) {
    // The part at z >= near (Sutherland–Hodgman against one plane), fanned into triangles.
    std::vector<Vec3> kept;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = local[triangle[k]];
      const Vec3& q = local[triangle[(k + 1) % 3]];
      if (p.z() >= near) kept.push_back(p);
      if ((p.z() >= near) != (q.z() >= near))
        kept.push_back(p + (q - p) * ((near - p.z()) / (q.z() - p.z())));
    }
    for (size_t k = 2; k < kept.size(); ++k)
      rasterize({kept[0], kept[k - 1], kept[k]}, camera, depth);
  }
  return std::move(depth);
}

}  // namespace rangefill
