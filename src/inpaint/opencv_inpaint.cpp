#include "rangefill/inpaint/opencv_inpaint.h"

#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>

namespace rangefill {

std::string OpenCvInpainter::name() const {
  return flags_ == cv::INPAINT_TELEA ? "telea" : "ns";
}

void OpenCvInpainter::inpaint(cv::InputArray depth_in, cv::InputArray mask_in,
                              cv::OutputArray out) const {
  check_inpaint_arguments(depth_in, mask_in, name());
  const cv::Mat depth = depth_in.getMat(), mask = mask_in.getMat();
  if (cv::countNonZero(mask) == 0) {
    depth.copyTo(out);
    return;
  }
  // #25389: a masked ring keeps the real mask off the top and left border. Masked values are
  // zeroed so that nothing (NaN included) leaks from them.
  cv::Mat clean = depth.clone(), padded, padded_mask;
  clean.setTo(0, mask);
  cv::copyMakeBorder(clean, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
  cv::copyMakeBorder(mask, padded_mask, 1, 1, 1, 1, cv::BORDER_CONSTANT, 255);

  cv::Mat restored;
  if (flags_ == cv::INPAINT_TELEA) {
    // #25404: work on CV_16U, the known range mapped onto [0, 65535].
    double lowest = 0, highest = 0;
    cv::minMaxLoc(depth, &lowest, &highest, nullptr, nullptr, mask == 0);
    const double scale = highest > lowest ? 65535.0 / (highest - lowest) : 1.0;
    cv::Mat quantized;
    padded.convertTo(quantized, CV_16U, scale, -lowest * scale);
    cv::inpaint(quantized, padded_mask, restored, radius_, flags_);
    restored.convertTo(restored, CV_32F, 1.0 / scale, lowest);
  } else {
    cv::inpaint(padded, padded_mask, restored, radius_, flags_);
  }
  // Known pixels are returned exactly as given, whatever the round trip did to them.
  depth.copyTo(out);
  restored(cv::Rect(1, 1, depth.cols, depth.rows)).copyTo(out.getMat(), mask);
}

}  // namespace rangefill
