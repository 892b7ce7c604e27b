#include "rangefill/inpaint/foe_model.h"

#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "foe_samples.h"
#include "rangefill/core/errors.h"
#include "rangefill/inpaint/inpainters.h"

namespace rangefill {
namespace {

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
  EXPECT_EQ(load_foe_model(InpainterOptions{}.foe.model).name, "depth");  // the default
}

}  // namespace
}  // namespace rangefill
