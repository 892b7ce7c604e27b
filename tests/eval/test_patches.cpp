#include "rangefill/eval/patches.h"
#include "rangefill/inpaint/inpainters.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "support.h"

namespace rangefill {
namespace {

// Patches of a sphere: as many as asked, each size × size with at most max_unseen of its pixels
// unseen, normalised depth within [0, 1] where seen; the same for a seed, others for another.
TEST(DepthPatches, CutsPatchesOfTheAskedSizeDeterministically) {
  const Mesh sphere = testing::make_sphere(24);
  PatchOptions options;
  options.size = 16;
  options.count = 6;
  const std::vector<DepthPatch> patches = depth_patches(sphere, options);
  ASSERT_EQ(patches.size(), 6u);
  for (const DepthPatch& patch : patches) {
    EXPECT_EQ(patch.depth.size(), cv::Size(16, 16));
    EXPECT_EQ(patch.depth.type(), CV_32F);
    EXPECT_GE(cv::countNonZero(patch.seen), (1 - options.max_unseen) * 256);
    double lowest = 0, highest = 0;
    cv::minMaxLoc(patch.depth, &lowest, &highest, nullptr, nullptr, patch.seen);
    EXPECT_GE(lowest, -1e-6);
    EXPECT_LE(highest, 1 + 1e-6);
    EXPECT_GT(patch.mean_edges_per_unit, 0);
  }
  const std::vector<DepthPatch> again = depth_patches(sphere, options);
  EXPECT_EQ(cv::norm(patches[0].depth, again[0].depth, cv::NORM_INF), 0);
  options.seed = 2;
  EXPECT_GT(cv::norm(patches[0].depth, depth_patches(sphere, options)[0].depth, cv::NORM_INF), 0);
}

// A blob mask covers its share of the patch and stays `margin` pixels from the border.
TEST(BlobMask, CoversItsShareAwayFromTheBorder) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const cv::Mat mask = blob_mask({32, 32}, 0.1, 0.3, 4, seed);
    const double share = cv::countNonZero(mask) / 1024.0;
    EXPECT_GE(share, 0.1) << seed;
    EXPECT_LE(share, 0.3) << seed;
    cv::Mat inner = cv::Mat::zeros(32, 32, CV_8U);
    inner(cv::Rect(4, 4, 24, 24)).setTo(255);
    EXPECT_EQ(cv::countNonZero(mask & ~inner), 0) << seed;
  }
}

// A hole sample of a plane patch with a plane trend leaves a zero residual, which the harmonic
// back-end restores exactly: RMSE 0.
TEST(HoleSample, APlaneRestoresExactly) {
  DepthPatch patch;
  patch.depth = cv::Mat(20, 20, CV_32F);
  for (int r = 0; r < 20; ++r) {
    for (int c = 0; c < 20; ++c) patch.depth.at<float>(r, c) = 0.02f * c + 0.01f * r;
  }
  patch.seen = cv::Mat(20, 20, CV_8U, cv::Scalar(255));
  cv::Mat mask = cv::Mat::zeros(20, 20, CV_8U);
  mask(cv::Rect(7, 6, 5, 6)).setTo(255);
  const HoleSample sample = make_hole_sample(patch, mask, TrendKind::plane);
  EXPECT_EQ(cv::countNonZero(sample.mask), 30);
  EXPECT_LT(cv::norm(sample.truth, cv::NORM_INF), 1e-5);
  EXPECT_LT(restoration_rmse(sample, *make_inpainter("harmonic")), 1e-5);
}

}  // namespace
}  // namespace rangefill
