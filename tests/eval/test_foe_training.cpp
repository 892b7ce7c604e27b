#include "rangefill/eval/foe_training.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "support.h"

namespace rangefill {
namespace {

// Smooth random surfaces (sums of a few waves) with blob masks, as residual samples.
std::vector<HoleSample> wave_samples(int count, int size, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> frequency(0.1, 0.6), phase(0, 6.3), amplitude(-0.05, 0.05);
  std::vector<HoleSample> samples;
  for (int s = 0; s < count; ++s) {
    DepthPatch patch{cv::Mat(size, size, CV_32F, cv::Scalar(0)),
                     cv::Mat(size, size, CV_8U, cv::Scalar(255))};
    for (int wave = 0; wave < 3; ++wave) {
      const double fx = frequency(random), fy = frequency(random), p = phase(random),
                   a = amplitude(random);
      for (int r = 0; r < size; ++r) {
        for (int c = 0; c < size; ++c) {
          patch.depth.at<float>(r, c) += a * std::sin(fx * c + fy * r + p);
        }
      }
    }
    samples.push_back(make_hole_sample(patch, blob_mask(patch.depth.size(), 0.1, 0.3, 2, seed + s),
                                       TrendKind::none));
  }
  return samples;
}

// The implicit gradient at the MAP matches central finite differences of the objective.
TEST(FoeObjective, GradientMatchesFiniteDifferences) {
  const FoeObjective objective(wave_samples(2, 10, 1), 3, 2, 2);
  std::vector<double> theta = objective.initial_parameters();
  std::mt19937 random(2);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  for (double& t : theta) t += jitter(random);  // away from the symmetric start
  std::vector<double> gradient;
  objective.evaluate(theta, &gradient);
  ASSERT_EQ(static_cast<int>(gradient.size()), objective.parameter_count());
  for (int k = 0; k < objective.parameter_count(); ++k) {
    const double h = 1e-4 * std::max(1.0, std::abs(theta[k]));
    std::vector<double> up = theta, down = theta;
    up[k] += h;
    down[k] -= h;
    const double numeric =
        (objective.evaluate(up, nullptr) - objective.evaluate(down, nullptr)) / (2 * h);
    EXPECT_NEAR(gradient[k], numeric, 1e-6 * std::max(1.0, std::abs(numeric)) + 1e-9)
        << "parameter " << k;
  }
}

// The objective does not depend on the thread count.
TEST(FoeObjective, SameAtAnyThreadCount) {
  const std::vector<HoleSample> samples = wave_samples(5, 12, 3);
  const FoeObjective one(samples, 3, 4, 1), three(samples, 3, 4, 3);
  const std::vector<double> theta = one.initial_parameters();
  std::vector<double> g1, g3;
  EXPECT_EQ(one.evaluate(theta, &g1), three.evaluate(theta, &g3));
  EXPECT_EQ(g1, g3);
}

// A short training run lowers the loss on samples it never saw.
TEST(TrainFoe, ATinyRunLowersTheValidationLoss) {
  FoeTrainingOptions options;
  options.count = 4;
  options.iterations = 15;
  const FoeTraining training = train_foe(wave_samples(12, 16, 5), wave_samples(6, 16, 77), options);
  EXPECT_LT(training.training_loss_end, training.training_loss_start);
  EXPECT_LT(training.validation_loss_end, training.validation_loss_start);
  EXPECT_EQ(training.model.count(), 4);
  for (double alpha : training.model.alphas) EXPECT_GT(alpha, 0);
}

}  // namespace
}  // namespace rangefill
