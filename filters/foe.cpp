#include "foe.h"

#include <cmath>

#include <ceres/ceres.h>
#include <opencv2/imgproc.hpp>

#include "harmonic.h"

namespace rangefill {

FoeInpainter::FoeInpainter(FoeModel model, const FoeInferenceOptions& options)
    : model_(std::move(model)), options_(options) {}

namespace {

// E as a function of the masked pixels of a crop (the rest fixed), for Ceres.
class MaskedEnergy : public ceres::FirstOrderFunction {
 public:
  MaskedEnergy(const FoeModel& model, cv::Mat image, cv::Mat mask, std::vector<cv::Point> unknowns)
      : model_(model),
        image_(std::move(image)),
        mask_(std::move(mask)),
        unknowns_(std::move(unknowns)) {}

  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    for (size_t k = 0; k < unknowns_.size(); ++k) image_.at<double>(unknowns_[k]) = parameters[k];
    cv::Mat full_gradient;
    *cost = foe_energy_of_unknowns(model_, image_, mask_, gradient ? &full_gradient : nullptr);
    if (gradient) {
      for (size_t k = 0; k < unknowns_.size(); ++k) {
        gradient[k] = full_gradient.at<double>(unknowns_[k]);
      }
    }
    return std::isfinite(*cost);
  }
  int NumParameters() const override { return static_cast<int>(unknowns_.size()); }

 private:
  const FoeModel& model_;
  mutable cv::Mat image_;  // the crop; Evaluate writes the unknowns into it
  cv::Mat mask_;           // the crop's mask
  std::vector<cv::Point> unknowns_;
};

}  // namespace

void FoeInpainter::inpaint(cv::InputArray depth_in, cv::InputArray mask_in,
                           cv::OutputArray out) const {
  check_inpaint_arguments(depth_in, mask_in, name());
  const cv::Mat depth = depth_in.getMat(), mask = mask_in.getMat();
  cv::Mat start;
  HarmonicInpainter().inpaint(depth, mask, start);
  start.copyTo(out);
  if (cv::countNonZero(mask) == 0) return;

  const int margin = model_.size / 2 + 1;
  cv::Rect crop = cv::boundingRect(mask);
  crop.x -= margin;
  crop.y -= margin;
  crop.width += 2 * margin;
  crop.height += 2 * margin;
  crop &= cv::Rect(0, 0, depth.cols, depth.rows);
  const double divisor = foe_input_divisor(model_, start(crop), mask(crop));
  cv::Mat image;
  start(crop).convertTo(image, CV_64F, 1.0 / divisor);
  std::vector<cv::Point> unknowns;
  std::vector<double> parameters;
  for (int row = 0; row < crop.height; ++row) {
    for (int col = 0; col < crop.width; ++col) {
      if (!mask.at<std::uint8_t>(crop.y + row, crop.x + col)) continue;
      unknowns.emplace_back(col, row);
      parameters.push_back(image.at<double>(row, col));
    }
  }

  ceres::GradientProblemSolver::Options options;
  options.line_search_direction_type = ceres::LBFGS;
  options.max_num_iterations = options_.max_iterations;
  options.function_tolerance = options_.function_tolerance;
  options.logging_type = ceres::SILENT;
  ceres::GradientProblemSolver::Summary summary;
  ceres::GradientProblem problem(
      new MaskedEnergy(model_, image.clone(), mask(crop).clone(), unknowns));
  ceres::Solve(options, problem, parameters.data(), &summary);

  cv::Mat result = out.getMat();
  for (size_t k = 0; k < unknowns.size(); ++k) {
    const cv::Point p = unknowns[k] + crop.tl();
    result.at<float>(p) = static_cast<float>(parameters[k] * divisor);
  }
}

}  // namespace rangefill
