#include "rangefill/inpaint/foe.h"
#include "rangefill/inpaint/foe_model.h"

#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "rangefill/core/errors.h"
#include "rangefill/inpaint/inpainter.h"

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
  options.foe_start = "telea";
  options.foe_iterations = 0;
  make_inpainter("foe", options)->inpaint(image, mask, unrefined);
  EXPECT_EQ(cv::norm(unrefined, telea, cv::NORM_INF), 0);
  options.foe_iterations = 10;
  make_inpainter("foe", options)->inpaint(image, mask, refined);
  EXPECT_EQ(cv::norm(refined, image, cv::NORM_INF, ~mask), 0);
  const FoeModel model = load_foe_model(options.model);
  const auto energy = [&](const cv::Mat& x) {
    cv::Mat x64;
    x.convertTo(x64, CV_64F);
    return foe_energy_of_unknowns(model, x64, mask);
  };
  EXPECT_LT(energy(refined), energy(telea));
  for (const auto& spoil : std::vector<std::function<void(InpainterOptions&)>>{
           [](InpainterOptions& o) { o.foe_start = "foe"; },
           [](InpainterOptions& o) { o.foe_start = "foe:roth-black"; },
           [](InpainterOptions& o) { o.foe_start = "nothing"; },
           [](InpainterOptions& o) { o.foe_tolerance = -1; },
           [](InpainterOptions& o) { o.foe_iterations = -1; }}) {
    InpainterOptions bad;
    spoil(bad);
    EXPECT_THROW(make_inpainter("foe", bad), InvalidInput);
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

// The depth model ships too, with the command that made it.
TEST(FoeModel, DepthModelShipsWithItsTrainingCommand) {
  const FoeModel model = load_foe_model("depth");
  EXPECT_EQ(model.size, 5);
  EXPECT_EQ(model.count(), 24);
  EXPECT_NE(model.training.find("rangefill train-foe"), std::string::npos);
  EXPECT_EQ(load_foe_model(InpainterOptions{}.model).name, "depth");  // the default
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
// rise from there to the rim; measured: depth 0.019, roth-black 0.026).
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
