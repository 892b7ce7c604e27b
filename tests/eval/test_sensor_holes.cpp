// Sensor-like holes of the depth benchmarks.
#include "rangefill/eval/sensor_holes.h"

#include <gtest/gtest.h>

#include "depth_scenes.h"

namespace rangefill {
namespace {

using namespace testing::depth_scenes;

// Punched pixels are valid ones, about `fraction` of them, the same for a seed, other for another;
// with a depth edge, shadows lie on its far side.
TEST(PunchDepthHoles, PunchesValidPixelsDeterministically) {
  cv::Mat depth(kSize, CV_16U, cv::Scalar(3000));
  depth.colRange(300, 640).setTo(1500);
  depth(cv::Rect(0, 0, 640, 20)).setTo(0);
  SensorHoleOptions options;
  options.fraction = 0.05;
  const cv::Mat punched = punch_depth_holes(depth, options);
  const double valid = cv::countNonZero(depth);
  EXPECT_EQ(cv::countNonZero(punched & (depth == 0)), 0);
  EXPECT_NEAR(cv::countNonZero(punched) / valid, 0.05, 0.005);
  EXPECT_EQ(cv::norm(punched, punch_depth_holes(depth, options), cv::NORM_INF), 0);
  options.seed = 2;
  EXPECT_GT(cv::norm(punched, punch_depth_holes(depth, options), cv::NORM_L1), 0);
  // Shadows: left of the near surface, on the far pixels next to the edge.
  EXPECT_GT(cv::countNonZero(punched.col(299)), 20);
  EXPECT_GT(cv::countNonZero(punched.col(299)), 2 * cv::countNonZero(punched.col(300)));
}

}  // namespace
}  // namespace rangefill
