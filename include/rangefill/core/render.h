// A z-buffer renderer of meshes into depth maps (no OpenGL): the depth benchmarks' scenes and the
// pictures of repaired holes.
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "rangefill/core/mesh.h"

namespace rangefill {

/// A pinhole camera in OpenCV's convention: x right, y down, z forward; pixel (col, row) has its
/// centre at (u, v) = (col, row), so the image centre of a W×H image is ((W − 1)/2, (H − 1)/2).
struct CameraIntrinsics {
  double fx = 525, fy = 525, cx = 319.5, cy = 239.5;  // PrimeSense defaults, 640×480
};

/// The world → camera transform of a camera at `eye` looking at `target`, with `up` (world)
/// pointing up in the image (−y of the camera). Throws InvalidInput if eye = target or up is
/// parallel to the view.
Eigen::Isometry3d look_at(const Vec3& eye, const Vec3& target, const Vec3& up);

/// Renders the depth map (z along the optical axis, metres, CV_32FC1; 0 where no surface) of a mesh
/// seen by a camera with pose `world_to_camera`, by z-buffering: every triangle, either side, is
/// rasterised at the pixel centres inside it (edges shared by two triangles are drawn by both, so
/// that a closed surface shows no cracks), depth interpolated perspective-correctly (1/z is linear
/// in the image), the nearest surface winning. Triangles are clipped at z = `near`.
cv::Mat render_depth(const Mesh& mesh, const CameraIntrinsics& camera,
                     const Eigen::Isometry3d& world_to_camera, cv::Size size, double near = 1e-3);

}  // namespace rangefill
