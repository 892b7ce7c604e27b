#include "hole_pictures.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/core/render.h"

namespace rangefill::cli {

namespace {

// How the hole is seen: a camera on the fill's normal, and the ball of surface round it.
struct View {
  Vec3 centre = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  double radius = 0;  // of the surface shown
};

View view_of_fill(const Mesh& repaired, const std::vector<int>& generated) {
  View view;
  Vec3 area = Vec3::Zero();
  double total = 0;
  for (int f : generated) {
    const Vec3 cross = triangle_cross(repaired, f);
    area += cross;
    total += cross.norm();
    for (int v : repaired.triangles[f]) view.centre += cross.norm() * repaired.positions[v];
  }
  view.centre /= 3 * std::max(total, 1e-300);
  if (area.norm() > 0) view.normal = area.normalized();
  double extent = 0;
  for (int f : generated) {
    for (int v : repaired.triangles[f]) {
      extent = std::max(extent, (repaired.positions[v] - view.centre).norm());
    }
  }
  view.radius = 2.5 * std::max(extent, 1e-9);
  return view;
}

// The faces of `mesh` with a vertex in the view's ball.
std::vector<int> faces_in_view(const Mesh& mesh, const View& view) {
  std::vector<int> faces;
  for (int f = 0; f < mesh.face_count(); ++f) {
    for (int v : mesh.triangles[f]) {
      if ((mesh.positions[v] - view.centre).norm() <= view.radius) {
        faces.push_back(f);
        break;
      }
    }
  }
  return faces;
}

// Grey levels of a depth map lit from the camera: |n·z| of the normals its differences give; the
// background light grey. Where `tint` (CV_8U) is set the colour is orange.
cv::Mat shade(const cv::Mat& depth, const CameraIntrinsics& camera, const cv::Mat& tint) {
  cv::Mat picture(depth.size(), CV_8UC3, cv::Scalar(235, 235, 235));
  const auto point = [&](int row, int col) {
    const double z = depth.at<float>(row, col);
    return Vec3((col - camera.cx) * z / camera.fx, (row - camera.cy) * z / camera.fy, z);
  };
  for (int row = 0; row + 1 < depth.rows; ++row) {
    for (int col = 0; col + 1 < depth.cols; ++col) {
      if (!(depth.at<float>(row, col) > 0) || !(depth.at<float>(row, col + 1) > 0) ||
          !(depth.at<float>(row + 1, col) > 0)) {
        continue;
      }
      const Vec3 p = point(row, col);
      const Vec3 n = (point(row, col + 1) - p).cross(point(row + 1, col) - p);
      if (!(n.norm() > 0)) continue;
      const double light = 0.25 + 0.75 * std::abs(n.normalized().dot(p.normalized()));
      const cv::Vec3d colour = !tint.empty() && tint.at<std::uint8_t>(row, col)
                                   ? cv::Vec3d(60, 150, 255)  // BGR orange
                                   : cv::Vec3d(225, 225, 225);
      picture.at<cv::Vec3b>(row, col) = cv::Vec3b(cv::saturate_cast<uchar>(colour[0] * light),
                                                  cv::saturate_cast<uchar>(colour[1] * light),
                                                  cv::saturate_cast<uchar>(colour[2] * light));
    }
  }
  return picture;
}

}  // namespace

cv::Mat hole_picture(const Mesh& input, const Mesh& repaired, int hole, int size) {
  std::vector<int> generated;
  for (int f = 0; f < repaired.face_count(); ++f) {
    if (repaired.face_hole[f] == hole) generated.push_back(f);
  }
  if (generated.empty()) return cv::Mat();
  const View view = view_of_fill(repaired, generated);
  const double distance = 3 * view.radius;
  CameraIntrinsics camera;
  camera.cx = camera.cy = (size - 1) / 2.0;
  camera.fx = camera.fy = 0.5 * size * distance / view.radius;  // the ball fills the picture
  const Vec3 up = view.normal.unitOrthogonal();
  const Eigen::Isometry3d pose = look_at(view.centre + distance * view.normal, view.centre, up);
  const cv::Size pixels(size, size);

  const cv::Mat before =
      render_depth(extract_faces(input, faces_in_view(input, view)), camera, pose, pixels);
  const cv::Mat after =
      render_depth(extract_faces(repaired, faces_in_view(repaired, view)), camera, pose, pixels);
  const cv::Mat fill = render_depth(extract_faces(repaired, generated), camera, pose, pixels);
  // The fill shows where it is the nearest surface.
  cv::Mat tint = (fill > 0) & (cv::abs(fill - after) <= 1e-6 * distance);

  cv::Mat picture;
  cv::hconcat(shade(before, camera, cv::Mat()), shade(after, camera, tint), picture);
  return picture;
}

}  // namespace rangefill::cli
