#include "rangefill/inpaint/foe_energy.h"

#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "foe_samples.h"
#include "rangefill/core/errors.h"

namespace rangefill {
namespace {

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

// The Hessian over the unknowns matches central finite differences of the gradient there.
TEST(FoeHessian, MatchesFiniteDifferencesOfTheGradient) {
  const FoeModel model = random_model(3);
  cv::Mat x = random_image(8, 9, 4);
  cv::Mat mask = cv::Mat::zeros(x.size(), CV_8U);
  mask(cv::Rect(2, 2, 4, 3)).setTo(255);
  mask.at<std::uint8_t>(7, 0) = 255;  // on the border, under fewer cliques
  std::vector<cv::Point> unknowns;
  cv::findNonZero(mask, unknowns);
  const Eigen::MatrixXd hessian(foe_hessian_of_unknowns(model, x, mask));
  ASSERT_EQ(hessian.rows(), static_cast<Eigen::Index>(unknowns.size()));
  const double h = 1e-6;
  for (size_t b = 0; b < unknowns.size(); ++b) {
    cv::Mat up, down;
    const double saved = x.at<double>(unknowns[b]);
    x.at<double>(unknowns[b]) = saved + h;
    foe_energy_of_unknowns(model, x, mask, &up);
    x.at<double>(unknowns[b]) = saved - h;
    foe_energy_of_unknowns(model, x, mask, &down);
    x.at<double>(unknowns[b]) = saved;
    for (size_t a = 0; a < unknowns.size(); ++a) {
      const double numeric = (up.at<double>(unknowns[a]) - down.at<double>(unknowns[a])) / (2 * h);
      EXPECT_NEAR(hessian(a, b), numeric, 1e-5 * std::max(1.0, std::abs(numeric)))
          << a << ", " << b;
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

}  // namespace
}  // namespace rangefill
