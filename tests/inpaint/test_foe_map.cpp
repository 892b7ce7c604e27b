#include "rangefill/inpaint/foe_map.h"

#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "foe_samples.h"
#include "rangefill/core/errors.h"
#include "rangefill/inpaint/foe_energy.h"
#include "rangefill/inpaint/inpainters.h"

namespace rangefill {
namespace {

// Newton MAP inference ends at a stationary point of E over the unknowns, below the harmonic start,
// with the known pixels untouched and the unknowns' input values unread.
TEST(FoeMap, ReachesAStationaryPointBelowTheStart) {
  for (unsigned seed : {5u, 6u, 7u}) {
    FoeModel model = random_model(seed);
    for (cv::Mat& filter : model.filters) filter -= cv::mean(filter)[0];
    cv::Mat image(20, 22, CV_64F), mask = cv::Mat::zeros(image.size(), CV_8U);
    for (int r = 0; r < image.rows; ++r) {
      for (int c = 0; c < image.cols; ++c) {
        image.at<double>(r, c) = 0.3 * std::sin(0.4 * c + seed) * std::cos(0.3 * r) + 0.01 * r;
        const double u = (c - 11) / 6.0, v = (r - 9) / 4.0;
        if (u * u + v * v < 1) mask.at<std::uint8_t>(r, c) = 255;
      }
    }
    FoeMapOptions options;
    options.function_tolerance = 1e-15;
    options.gradient_tolerance = 1e-12;
    options.method = FoeMapMethod::newton;
    cv::Mat garbage = image.clone();
    garbage.setTo(1e6, mask);
    const cv::Mat x = foe_map(model, garbage, mask, options);
    EXPECT_EQ(cv::norm(x, image, cv::NORM_INF, ~mask), 0) << seed;
    cv::Mat gradient;
    const double energy = foe_energy_of_unknowns(model, x, mask, &gradient);
    double largest = 0;
    cv::minMaxLoc(cv::abs(gradient), nullptr, &largest, nullptr, nullptr, mask);
    EXPECT_LT(largest, 1e-9) << seed;
    cv::Mat image32, start32, start;
    image.convertTo(image32, CV_32F);
    make_inpainter("harmonic")->inpaint(image32, mask, start32);
    start32.convertTo(start, CV_64F);
    EXPECT_LT(energy, foe_energy_of_unknowns(model, start, mask)) << seed;
  }
}

// The fast method (single precision, stops on the decrease of E) ends where the exact one does:
// within 1e-4 of its energy (or below) and 1e-2 of the image's range at every unknown, on a
// smooth surface with bumps and a blob mask, under every shipped model.
TEST(FoeMap, LbfgsEndsWhereNewtonDoes) {
  cv::Mat image(64, 64, CV_64F), mask = cv::Mat::zeros(image.size(), CV_8U);
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      const double u = c / 64.0 - 0.5, v = r / 64.0 - 0.5;
      image.at<double>(r, c) = 0.5 + 0.3 * u - 0.2 * v + 0.4 * (u * u + 0.7 * v * v) +
                               0.03 * std::sin(12 * u) * std::cos(9 * v);
      if ((u + 0.1) * (u + 0.1) + v * v < 0.06 ||
          (u - 0.3) * (u - 0.3) + (v - 0.3) * (v - 0.3) < 0.01) {
        mask.at<std::uint8_t>(r, c) = 255;
      }
    }
  }
  for (const std::string& name : shipped_foe_models()) {
    const FoeModel model = load_foe_model(name);
    FoeMapOptions exact;
    exact.method = FoeMapMethod::newton;
    exact.function_tolerance = 0;
    const cv::Mat newton = foe_map(model, image, mask, exact);
    const cv::Mat lbfgs = foe_map(model, image, mask);
    EXPECT_EQ(cv::norm(lbfgs, image, cv::NORM_INF, ~mask), 0) << name;
    const double e_newton = foe_energy_of_unknowns(model, newton, mask);
    const double e_lbfgs = foe_energy_of_unknowns(model, lbfgs, mask);
    EXPECT_LT(e_lbfgs, e_newton + 1e-4 * std::abs(e_newton)) << name;
    EXPECT_LT(cv::norm(lbfgs, newton, cv::NORM_INF, mask), 1e-2) << name;
    std::printf("%s: E lbfgs %.6f newton %.6f, largest difference %.2e\n", name.c_str(), e_lbfgs,
                e_newton, cv::norm(lbfgs, newton, cv::NORM_INF, mask));
  }
}

// Clique weights (foe_clique_weights of a guide with an edge) enter E, ∇E and both methods alike:
// Newton ends at a stationary point of the weighted E, lbfgs run to convergence where Newton does
// (its preconditioner does not see the weights, so it takes more steps), and weights of 1 are no
// weights.
TEST(FoeMap, CliqueWeightsEnterBothMethods) {
  const FoeModel model = load_foe_model("depth");
  cv::Mat image(40, 40, CV_64F), mask = cv::Mat::zeros(image.size(), CV_8U);
  cv::Mat guide(image.size(), CV_32FC3, cv::Scalar(200, 200, 200));
  guide.colRange(0, 20).setTo(cv::Scalar(20, 40, 60));
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      image.at<double>(r, c) = (c < 20 ? 0.2 : 0.8) + 0.01 * r;
      if ((c - 20) * (c - 20) + (r - 20) * (r - 20) < 81) mask.at<std::uint8_t>(r, c) = 255;
    }
  }
  const cv::Mat weights = foe_clique_weights(guide, model.size, 10);
  double lowest = 0, highest = 0;
  cv::minMaxLoc(weights, &lowest, &highest);
  EXPECT_LT(lowest, 1e-2);
  EXPECT_EQ(highest, 1);
  FoeMapOptions exact;
  exact.method = FoeMapMethod::newton;
  exact.function_tolerance = 0;
  const cv::Mat newton = foe_map(model, image, mask, exact, weights);
  cv::Mat gradient;
  const double e_newton = foe_energy_of_unknowns(model, newton, mask, &gradient, weights);
  double largest = 0;
  cv::minMaxLoc(cv::abs(gradient), nullptr, &largest, nullptr, nullptr, mask);
  EXPECT_LT(largest, 1e-9);
  FoeMapOptions longer;
  longer.max_iterations = 2000;
  longer.function_tolerance = 0;
  const cv::Mat lbfgs = foe_map(model, image, mask, longer, weights);
  EXPECT_EQ(cv::norm(lbfgs, image, cv::NORM_INF, ~mask), 0);
  const double e_lbfgs = foe_energy_of_unknowns(model, lbfgs, mask, nullptr, weights);
  EXPECT_LT(e_lbfgs, e_newton + 1e-4 * std::abs(e_newton));
  EXPECT_LT(cv::norm(lbfgs, newton, cv::NORM_INF, mask), 1e-2);
  const cv::Mat ones = cv::Mat::ones(image.size(), CV_64F);
  EXPECT_LT(
      cv::norm(foe_map(model, image, mask, {}, ones), foe_map(model, image, mask), cv::NORM_INF),
      1e-6);
}

// With start_from_image, inference starts from the unknowns' values given: zero steps return them
// unchanged, and steps lower E from there. A start that is not finite is refused.
TEST(FoeMap, StartsFromTheImageWhenAsked) {
  const FoeModel model = load_foe_model("depth");
  cv::Mat image(32, 32, CV_64F), mask = cv::Mat::zeros(image.size(), CV_8U);
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      image.at<double>(r, c) = 0.5 + 0.01 * c + 0.1 * std::sin(0.3 * r) * std::cos(0.2 * c);
      if ((r - 15) * (r - 15) + (c - 17) * (c - 17) < 64) mask.at<std::uint8_t>(r, c) = 255;
    }
  }
  cv::Mat start = image.clone();
  cv::Mat noise(image.size(), CV_64F);
  cv::randu(noise, -0.2, 0.2);
  cv::add(start, noise, start, mask);
  FoeMapOptions options;
  options.start_from_image = true;
  options.max_iterations = 0;
  EXPECT_EQ(cv::norm(foe_map(model, start, mask, options), start, cv::NORM_INF), 0);
  options.max_iterations = 100;
  const cv::Mat x = foe_map(model, start, mask, options);
  EXPECT_EQ(cv::norm(x, image, cv::NORM_INF, ~mask), 0);
  const double from_start = foe_energy_of_unknowns(model, start, mask);
  EXPECT_LT(foe_energy_of_unknowns(model, x, mask), 0.5 * from_start);
  start.at<double>(15, 17) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(foe_map(model, start, mask, options), InvalidInput);
}

}  // namespace
}  // namespace rangefill
