#include "rangefill/foe.h"
#include "foe.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "rangefill/errors.h"

namespace rangefill {
namespace {

// A small random model: 4 filters of 3×3, alphas in [0.5, 2].
FoeModel random_model(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> tap(-1, 1), alpha(0.5, 2);
  FoeModel model;
  model.name = "random";
  model.size = 3;
  model.input_scale = 3;
  for (int i = 0; i < 4; ++i) {
    cv::Mat filter(3, 3, CV_64F);
    for (double& v : cv::Mat_<double>(filter)) v = tap(random);
    model.filters.push_back(filter);
    model.alphas.push_back(alpha(random));
  }
  return model;
}

cv::Mat random_image(int rows, int cols, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> value(0, 0.5);
  cv::Mat image(rows, cols, CV_64F);
  for (double& v : cv::Mat_<double>(image)) v = value(random);
  return image;
}

// ∇E from foe_energy matches central finite differences at every pixel.
TEST(FoeEnergy, GradientMatchesFiniteDifferences) {
  const FoeModel model = random_model(1);
  cv::Mat x = random_image(7, 9, 2), gradient;
  foe_energy(model, x, &gradient);
  const double h = 1e-6;
  for (int r = 0; r < x.rows; ++r) {
    for (int c = 0; c < x.cols; ++c) {
      const double saved = x.at<double>(r, c);
      x.at<double>(r, c) = saved + h;
      const double up = foe_energy(model, x);
      x.at<double>(r, c) = saved - h;
      const double down = foe_energy(model, x);
      x.at<double>(r, c) = saved;
      EXPECT_NEAR(gradient.at<double>(r, c), (up - down) / (2 * h), 1e-6) << r << ", " << c;
    }
  }
}

// A constant image has zero energy under zero-mean filters, positive otherwise.
TEST(FoeEnergy, ConstantImageUnderZeroMeanFilters) {
  FoeModel model = random_model(3);
  for (cv::Mat& filter : model.filters) filter -= cv::mean(filter)[0];
  EXPECT_NEAR(foe_energy(model, cv::Mat(6, 6, CV_64F, cv::Scalar(0.7))), 0, 1e-12);
  EXPECT_GT(foe_energy(model, random_image(6, 6, 4)), 0);
}

// Writing a model and reading it back gives the same numbers, bit for bit.
TEST(FoeModel, RoundTripsThroughYaml) {
  FoeModel model = random_model(5);
  model.normalisation = "residual depth";
  model.training = "none: a test";
  const FoeModel back = parse_foe_model(serialize_foe_model(model), "mem");
  EXPECT_EQ(back.name, model.name);
  EXPECT_EQ(back.size, model.size);
  EXPECT_EQ(back.alphas, model.alphas);
  EXPECT_EQ(back.input_scale, model.input_scale);
  EXPECT_EQ(back.normalisation, model.normalisation);
  EXPECT_EQ(back.training, model.training);
  ASSERT_EQ(back.count(), model.count());
  for (int i = 0; i < model.count(); ++i) {
    EXPECT_EQ(cv::norm(back.filters[i], model.filters[i], cv::NORM_INF), 0) << i;
  }
}

// Roth & Black's 5×5 model ships with the library: 24 filters, positive alphas.
TEST(FoeModel, RothBlackShips) {
  const FoeModel model = load_foe_model("roth-black");
  EXPECT_EQ(model.size, 5);
  EXPECT_EQ(model.count(), 24);
  EXPECT_EQ(model.input_scale, 255);
  EXPECT_THROW(load_foe_model("/no/such/model.yml"), InvalidInput);
  EXPECT_THROW(parse_foe_model("3 2\n0 1 2\n", "bad.foe"), InvalidInput);
  EXPECT_THROW(parse_foe_model("%YAML:1.0\n---\nformat_version: 99\n", "bad.yml"), InvalidInput);
}

// MAP inference keeps known pixels and restores a plane closely; the energy at the result is no
// higher than at the harmonic start.
TEST(FoeInpainter, RestoresAPlane) {
  const int n = 48;
  cv::Mat image(n, n, CV_32F), mask = cv::Mat::zeros(n, n, CV_8U), out;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      image.at<float>(r, c) = static_cast<float>(0.004 * c - 0.003 * r + 0.5);
      if ((r - 24) * (r - 24) + (c - 24) * (c - 24) < 100) mask.at<std::uint8_t>(r, c) = 255;
    }
  }
  const FoeInpainter foe(load_foe_model("roth-black"));
  cv::Mat input = image.clone();
  input.setTo(0, mask);
  foe.inpaint(input, mask, out);
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
  EXPECT_LT(worst, 2e-3);  // 1.5 % of the plane's slope across the hole
}

}  // namespace
}  // namespace rangefill
