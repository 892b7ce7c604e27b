#include "eval/fast_bilateral_solver.h"

#include <opencv2/ximgproc/edge_filter.hpp>

extern "C" __attribute__((visibility("default"))) void rangefill_fast_bilateral_solver(
    const cv::Mat& depth, const cv::Mat& color, const cv::Mat& to_fill, cv::Mat& out) {
  cv::Mat depth32, confidence;
  depth.convertTo(depth32, CV_32F);
  confidence = (depth > 0) & (to_fill == 0);
  confidence.convertTo(confidence, CV_32F, 1.0 / 255);
  cv::Mat solved;
  cv::ximgproc::fastBilateralSolverFilter(color, depth32, confidence, solved);
  solved.convertTo(out, CV_16U);
}
