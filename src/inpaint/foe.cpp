#include "rangefill/inpaint/foe.h"

#include <opencv2/imgproc.hpp>

#include "rangefill/core/errors.h"
#include "rangefill/inpaint/foe_energy.h"
#include "rangefill/inpaint/harmonic.h"

namespace rangefill {

FoeInpainter::FoeInpainter(FoeModel model, const FoeMapOptions& options,
                           std::unique_ptr<Inpainter> start, cv::Mat clique_weights)
    : model_(std::move(model)),
      options_(options),
      start_(std::move(start)),
      clique_weights_(std::move(clique_weights)) {
  if (start_) options_.start_from_image = true;
  if (!clique_weights_.empty() && clique_weights_.type() != CV_64FC1) {
    throw InvalidInput("foe: the clique weights must be CV_64FC1");
  }
}

std::unique_ptr<Inpainter> FoeInpainter::guided(const cv::Mat& guide, float sigma) const {
  return std::make_unique<FoeInpainter>(model_, options_,
                                        std::make_unique<HarmonicInpainter>(guide, sigma),
                                        foe_clique_weights(guide, model_.size, sigma));
}

void FoeInpainter::inpaint(cv::InputArray depth_in, cv::InputArray mask_in,
                           cv::OutputArray out) const {
  check_inpaint_arguments(depth_in, mask_in, name());
  const cv::Mat depth = depth_in.getMat(), mask = mask_in.getMat();
  depth.copyTo(out);
  if (cv::countNonZero(mask) == 0) return;
  if (!clique_weights_.empty() && clique_weights_.size() != depth.size()) {
    throw InvalidInput("foe: the clique weights' size differs from the depth's");
  }

  const int margin = model_.size / 2 + 1;
  cv::Rect crop = cv::boundingRect(mask);
  crop.x -= margin;
  crop.y -= margin;
  crop.width += 2 * margin;
  crop.height += 2 * margin;
  crop &= cv::Rect(0, 0, depth.cols, depth.rows);
  const double divisor = foe_input_divisor(model_, depth(crop), mask(crop));
  cv::Mat image;
  if (start_) {
    cv::Mat started;
    start_->inpaint(depth, mask, started);  // as that back-end would fill the image
    started(crop).convertTo(image, CV_64F, 1.0 / divisor);
  } else {
    depth(crop).convertTo(image, CV_64F, 1.0 / divisor);
  }
  const cv::Mat restored = foe_map(model_, image, mask(crop).clone(), options_,
                                   clique_weights_.empty() ? cv::Mat() : clique_weights_(crop));
  cv::Mat result = out.getMat();
  for (int row = 0; row < crop.height; ++row) {
    for (int col = 0; col < crop.width; ++col) {
      if (!mask.at<std::uint8_t>(crop.y + row, crop.x + col)) continue;
      result.at<float>(crop.y + row, crop.x + col) =
          static_cast<float>(restored.at<double>(row, col) * divisor);
    }
  }
}

}  // namespace rangefill
