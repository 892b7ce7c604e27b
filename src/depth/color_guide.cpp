#include "depth/color_guide.h"

#include <opencv2/imgproc.hpp>

#include "rangefill/core/errors.h"

namespace rangefill {

cv::Mat guide_color(const cv::Mat& color, cv::Size size, const std::string& who) {
  if (color.empty()) return {};
  if (color.type() != CV_8UC3 && color.type() != CV_8UC1) {
    throw InvalidInput(who + ": the colour image must be 8-bit colour or grey, not " +
                       cv::typeToString(color.type()));
  }
  if (color.size() != size) {
    throw InvalidInput(who + ": the colour image is " + std::to_string(color.cols) + "x" +
                       std::to_string(color.rows) + " but the depth is " +
                       std::to_string(size.width) + "x" + std::to_string(size.height));
  }
  cv::Mat three = color;
  if (color.channels() == 1) cv::cvtColor(color, three, cv::COLOR_GRAY2BGR);
  cv::Mat guide;
  three.convertTo(guide, CV_32FC3);
  return guide;
}

}  // namespace rangefill
