#include "rangefill/fillers/mls.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace rangefill {
namespace {

// n points spread evenly over the unit sphere (Fibonacci lattice).
std::vector<Vec3> sphere_samples(int n) {
  std::vector<Vec3> points;
  const double golden = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z);
    points.emplace_back(r * std::cos(i * golden), r * std::sin(i * golden), z);
  }
  return points;
}

TEST(Mls, ProjectsOntoASphere) {
  const std::vector<Vec3> samples = sphere_samples(3000);
  const MlsSurface surface(samples, samples);  // normals = positions on the unit sphere
  std::mt19937 random(7);
  std::uniform_real_distribution<double> offset(-0.03, 0.03);
  double worst = 0, worst_normal = 0;
  for (int i = 0; i < 200; ++i) {
    const Vec3 on = sphere_samples(997)[static_cast<size_t>(i) * 4];
    const Vec3 query = on * (1 + offset(random)) + Vec3(offset(random), offset(random), 0) * 0.3;
    const auto projected = surface.project(query);
    ASSERT_TRUE(projected);
    worst = std::max(worst, std::abs(projected->point.norm() - 1));
    worst_normal = std::max(worst_normal, 1 - projected->normal.dot(projected->point.normalized()));
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(worst_normal, 1e-3);  // the normal points outwards, like the samples' normals
}

TEST(Mls, ProjectsOntoACylinder) {
  std::vector<Vec3> samples, normals;
  for (int i = 0; i < 80; ++i) {
    for (int k = 0; k < 40; ++k) {
      const double angle = 2 * M_PI * i / 80;
      samples.emplace_back(std::cos(angle), std::sin(angle), 0.08 * k - 1.6);
      normals.emplace_back(std::cos(angle), std::sin(angle), 0);
    }
  }
  const MlsSurface surface(samples, normals);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), height(-1, 1), radius(0.95, 1.05);
  double worst = 0;
  for (int i = 0; i < 200; ++i) {
    const double a = angle(random), r = radius(random);
    const auto projected = surface.project(Vec3(r * std::cos(a), r * std::sin(a), height(random)));
    ASSERT_TRUE(projected);
    worst = std::max(worst, std::abs(projected->point.head<2>().norm() - 1));
  }
  EXPECT_LT(worst, 1e-3);
}

TEST(Mls, ReferencePlaneOfAPlaneIsThePlane) {
  std::vector<Vec3> samples;
  const Vec3 normal = Vec3(1, 2, 2) / 3;
  const Vec3 u = normal.unitOrthogonal(), v = normal.cross(u);
  for (int i = -10; i <= 10; ++i) {
    for (int k = -10; k <= 10; ++k) samples.push_back(0.1 * i * u + 0.1 * k * v + Vec3(1, 1, 1));
  }
  const MlsSurface surface(samples, std::vector<Vec3>(samples.size(), normal));
  const ReferencePlane plane = surface.reference_plane(Vec3(1, 1, 1) + 0.3 * normal + 0.05 * u);
  EXPECT_NEAR(plane.normal.dot(normal), 1, 1e-9);
  EXPECT_NEAR(normal.dot(plane.origin - Vec3(1, 1, 1)), 0, 1e-9);
  const auto projected = surface.project(Vec3(1, 1, 1) - 0.2 * normal);
  ASSERT_TRUE(projected);
  EXPECT_NEAR(normal.dot(projected->point - Vec3(1, 1, 1)), 0, 1e-9);
}

// A surface may start empty (nothing to project onto) and take its samples later: a plane's,
// onto which a point then projects.
TEST(Mls, AnEmptySurfaceTakesSamplesLater) {
  MlsSurface surface({}, {});
  EXPECT_EQ(surface.size(), 0u);
  EXPECT_FALSE(surface.project(Vec3(0, 0, 1)));
  std::vector<Vec3> plane;
  for (int i = -3; i <= 3; ++i) {
    for (int j = -3; j <= 3; ++j) plane.emplace_back(0.1 * i, 0.1 * j, 0);
  }
  surface.add_samples(plane, {});
  EXPECT_EQ(surface.size(), plane.size());
  const auto projected = surface.project(Vec3(0.05, 0.02, 0.3));
  ASSERT_TRUE(projected);
  EXPECT_NEAR(projected->point.z(), 0, 1e-9);
}

TEST(Mls, TooFewSamplesGiveNothing) {
  const MlsSurface surface({Vec3(0, 0, 0), Vec3(1, 0, 0)}, {});
  EXPECT_FALSE(surface.project(Vec3(0.5, 0.5, 0)));
}

}  // namespace
}  // namespace rangefill
