#include "rangefill/inpaint/foe.h"

#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "rangefill/core/errors.h"
#include "rangefill/inpaint/foe_energy.h"
#include "rangefill/inpaint/inpainters.h"

namespace rangefill {
namespace {

// InpainterOptions::foe_start: foe refines another back-end's fill of the image (0 steps return it
// as it is, though foe itself works on a crop around the mask), lowering E; foe cannot start from
// itself, and negative limits are refused.
TEST(FoeInpainter, RefinesAnotherBackendsFill) {
  const int n = 40;
  cv::Mat image(n, n, CV_32F), mask = cv::Mat::zeros(n, n, CV_8U);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      image.at<float>(r, c) = static_cast<float>(0.5 + 0.02 * c + 0.001 * r * r);
      if ((r - 22) * (r - 22) + (c - 18) * (c - 18) < 64) mask.at<std::uint8_t>(r, c) = 255;
    }
  }
  image.setTo(0, mask);
  cv::Mat telea, unrefined, refined;
  make_inpainter("telea")->inpaint(image, mask, telea);
  InpainterOptions options;
  options.foe.start = "telea";
  options.foe.iterations = 0;
  make_inpainter("foe", options)->inpaint(image, mask, unrefined);
  EXPECT_EQ(cv::norm(unrefined, telea, cv::NORM_INF), 0);
  options.foe.iterations = 10;
  make_inpainter("foe", options)->inpaint(image, mask, refined);
  EXPECT_EQ(cv::norm(refined, image, cv::NORM_INF, ~mask), 0);
  const FoeModel model = load_foe_model(options.foe.model);
  const auto energy = [&](const cv::Mat& x) {
    cv::Mat x64;
    x.convertTo(x64, CV_64F);
    return foe_energy_of_unknowns(model, x64, mask);
  };
  EXPECT_LT(energy(refined), energy(telea));
  for (const auto& spoil : std::vector<std::function<void(InpainterOptions&)>>{
           [](InpainterOptions& o) { o.foe.start = "foe"; },
           [](InpainterOptions& o) { o.foe.start = "foe:roth-black"; },
           [](InpainterOptions& o) { o.foe.start = "nothing"; },
           [](InpainterOptions& o) { o.foe.tolerance = -1; },
           [](InpainterOptions& o) { o.foe.iterations = -1; }}) {
    InpainterOptions bad;
    spoil(bad);
    EXPECT_THROW(make_inpainter("foe", bad), InvalidInput);
  }
}

// The largest error of `inpainter`'s restoration of `surface` over a disk of radius 10 in a
// 48 × 48 image; the known pixels must come back exactly.
double disk_restoration_error(const Inpainter& inpainter, double (*surface)(int row, int col)) {
  const int n = 48;
  cv::Mat image(n, n, CV_32F), mask = cv::Mat::zeros(n, n, CV_8U), out;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      image.at<float>(r, c) = static_cast<float>(surface(r, c));
      if ((r - 24) * (r - 24) + (c - 24) * (c - 24) < 100) mask.at<std::uint8_t>(r, c) = 255;
    }
  }
  cv::Mat input = image.clone();
  input.setTo(0, mask);
  inpainter.inpaint(input, mask, out);
  double worst = 0;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      const double error = std::abs(out.at<float>(r, c) - image.at<float>(r, c));
      if (mask.at<std::uint8_t>(r, c)) {
        worst = std::max(worst, error);
      } else {
        EXPECT_EQ(out.at<float>(r, c), input.at<float>(r, c));
      }
    }
  }
  return worst;
}

// MAP inference with every shipped model restores a plane closely (its slope is 0.005 per pixel)
// and a paraboloid better than a harmonic fill does (0.05 at the hole's centre: the paraboloid's
// rise from there to the rim).
TEST(FoeInpainter, RestoresAPlaneAndAQuadric) {
  const auto plane = [](int r, int c) { return 0.004 * c - 0.003 * r + 0.5; };
  const auto paraboloid = [](int r, int c) {
    return 0.5 + 0.0005 * ((r - 24.0) * (r - 24.0) + (c - 20.0) * (c - 20.0));
  };
  const double harmonic = disk_restoration_error(*make_inpainter("harmonic"), paraboloid);
  for (const std::string& model : shipped_foe_models()) {
    const FoeInpainter foe(load_foe_model(model));
    EXPECT_LT(disk_restoration_error(foe, plane), 2e-3) << model;  // 0.4 px of slope
    EXPECT_LT(disk_restoration_error(foe, paraboloid), 0.6 * harmonic) << model;
  }
  EXPECT_GT(harmonic, 0.04);
}

}  // namespace
}  // namespace rangefill
