#include "rangefill/core/depth_image.h"

#include <limits>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"

namespace rangefill {
namespace {

// Millimetres and metres to metres; 0, negative and non-finite depths are invalid (0).
TEST(DepthImage, ReadsUnitsAndInvalidPixels) {
  const cv::Mat millimetres = (cv::Mat_<std::uint16_t>(1, 3) << 0, 1500, 65535);
  const cv::Mat metres = depth_in_metres(millimetres);
  ASSERT_EQ(metres.type(), CV_32FC1);
  EXPECT_FLOAT_EQ(metres.at<float>(0), 0);
  EXPECT_FLOAT_EQ(metres.at<float>(1), 1.5f);
  EXPECT_FLOAT_EQ(metres.at<float>(2), 65.535f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float infinity = std::numeric_limits<float>::infinity();
  const cv::Mat floats = (cv::Mat_<float>(1, 5) << 2.5f, nan, -1.f, infinity, 0.f);
  EXPECT_EQ(cv::countNonZero(depth_in_metres(floats)), 1);
  const cv::Mat invalid = invalid_depth_mask(floats);
  EXPECT_EQ(invalid.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(invalid), 4);
  EXPECT_EQ(invalid.at<std::uint8_t>(0), 0);
  EXPECT_THROW(check_depth_type(CV_8UC1, "here"), InvalidInput);
  EXPECT_NO_THROW(check_depth_type(CV_32FC1, "here"));
}

// Depths a relative `discontinuity` apart or less lie on one surface, either way round.
TEST(DepthImage, SameSurfaceWithinTheDiscontinuity) {
  EXPECT_TRUE(same_surface(1.0f, 1.05f, 0.05));
  EXPECT_TRUE(same_surface(1.05f, 1.0f, 0.05));
  EXPECT_FALSE(same_surface(1.0f, 1.06f, 0.05));
}

}  // namespace
}  // namespace rangefill
