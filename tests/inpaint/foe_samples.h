// Random FoE models and images for the FoE tests.
#pragma once

#include <random>

#include <opencv2/core.hpp>

#include "rangefill/inpaint/foe_model.h"

namespace rangefill {

// A small random model: 4 filters of 3×3, alphas in [0.5, 2].
inline FoeModel random_model(unsigned seed) {
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

inline cv::Mat random_image(int rows, int cols, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> value(0, 0.5);
  cv::Mat image(rows, cols, CV_64F);
  for (double& v : cv::Mat_<double>(image)) v = value(random);
  return image;
}

}  // namespace rangefill
