// The z-buffer renderer of the depth benchmarks.
#include "rangefill/core/render.h"

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"

#include "depth_scenes.h"
#include "support.h"

namespace rangefill {
namespace {

using namespace testing::depth_scenes;

// A quad of the plane z = 2 (camera looking along +z from the origin) renders as that plane; a
// tilted one as the analytic depth of its plane; outside it nothing.
TEST(RenderDepth, RendersPlanesExactly) {
  const Mesh quad =
      make_mesh({{-1, -1, 2}, {1, -1, 2}, {1, 1, 2}, {-1, 1, 2}}, {{0, 1, 2}, {0, 2, 3}});
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  const cv::Mat flat = render_depth(quad, kCamera, identity, kSize);
  // The quad spans ±1 m at 2 m: columns 319.5 ± 262.5, rows 239.5 ± 262.5 (all of them).
  EXPECT_EQ(cv::countNonZero(flat), (582 - 57 + 1) * 480);
  EXPECT_EQ(flat.at<float>(240, 320), 2.0f);
  EXPECT_EQ(flat.at<float>(240, 40), 0.0f);

  // Seen from (0.5, 0.3, −1) looking at (0, 0, 2): the plane z = 2 in camera coordinates.
  const Eigen::Isometry3d pose = look_at({0.5, 0.3, -1}, {0, 0, 2}, {0, -1, 0});
  const Vec3 normal_world(0, 0, 1);
  const Vec3 normal = pose.linear() * normal_world;
  const double d = normal.dot(pose * Vec3(0, 0, 2));
  const cv::Mat tilted = render_depth(quad, kCamera, pose, kSize);
  const cv::Mat truth = depth_image([&](const Vec3& r) { return plane_depth(r, normal, d); });
  EXPECT_GT(cv::countNonZero(tilted), 50000);
  EXPECT_LT(max_error(tilted, truth, tilted != 0), 1e-5);
}

// look_at puts the target on the optical axis, `up` up in the image, and keeps distances.
TEST(RenderDepth, LookAtPointsTheCamera) {
  const Eigen::Isometry3d pose = look_at({1, 2, 3}, {4, 6, 3}, {0, 0, 1});
  const Vec3 target = pose * Vec3(4, 6, 3);
  EXPECT_NEAR(target.x(), 0, 1e-12);
  EXPECT_NEAR(target.y(), 0, 1e-12);
  EXPECT_NEAR(target.z(), 5, 1e-12);
  EXPECT_LT((pose * Vec3(4, 6, 4) - target).y(), 0);  // up is −y
  EXPECT_NEAR(pose.linear().determinant(), 1, 1e-12);
  EXPECT_THROW(look_at({0, 0, 0}, {0, 0, 1}, {0, 0, 1}), InvalidInput);
}

// A closed sphere renders without cracks (every pixel inside its silhouette has depth) and close to
// the analytic sphere; the nearest surface wins over a plane behind it.
TEST(RenderDepth, RendersAClosedMeshWithoutCracks) {
  Mesh sphere = testing::make_sphere(24);
  for (Vec3& p : sphere.positions) p = p * 0.5 + Vec3(0, 0, 2);
  const Mesh wall =
      make_mesh({{-9, -9, 4}, {9, -9, 4}, {9, 9, 4}, {-9, 9, 4}}, {{0, 1, 2}, {0, 2, 3}});
  Mesh scene = sphere;
  for (const Triangle& t : wall.triangles) {
    scene.triangles.push_back(
        {t[0] + sphere.vertex_count(), t[1] + sphere.vertex_count(), t[2] + sphere.vertex_count()});
  }
  scene.positions.insert(scene.positions.end(), wall.positions.begin(), wall.positions.end());
  const cv::Mat depth = render_depth(scene, kCamera, Eigen::Isometry3d::Identity(), kSize);
  EXPECT_EQ(cv::countNonZero(depth), kSize.area());
  const cv::Mat truth = depth_image([](const Vec3& r) { return sphere_depth(r, {0, 0, 2}, 0.5); });
  // The inscribed polyhedron's silhouette lies within the sphere's; on the cap facing the camera
  // (up to 53° from the axis) depth is within a few times the chord error (0.16 mm).
  EXPECT_EQ(cv::countNonZero((depth < 3) & (truth == 0)), 0);
  EXPECT_LT(max_error(depth, truth, (truth > 0) & (truth < 1.7)), 1e-3);
}

}  // namespace
}  // namespace rangefill
