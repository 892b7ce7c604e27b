#include "rangefill/core/depth_image.h"

#include <algorithm>
#include <limits>

#include "rangefill/core/errors.h"

namespace rangefill {

void check_depth_type(int type, const std::string& who) {
  if (type != CV_16UC1 && type != CV_32FC1) {
    throw InvalidInput(who + ": depth must be CV_16UC1 (millimetres) or CV_32FC1 (metres), not " +
                       cv::typeToString(type));
  }
}

cv::Mat depth_in_metres(cv::InputArray depth) {
  cv::Mat z;
  depth.getMat().convertTo(z, CV_32F, depth.type() == CV_16UC1 ? 1e-3 : 1.0);
  for (int row = 0; row < z.rows; ++row) {
    float* values = z.ptr<float>(row);
    for (int col = 0; col < z.cols; ++col) {
      const float value = values[col];
      values[col] = value > 0 && value < std::numeric_limits<float>::infinity() ? value : 0;
    }
  }
  return z;
}

cv::Mat invalid_depth_mask(cv::InputArray depth) {
  check_depth_type(depth.type(), "invalid_depth_mask");
  return depth_in_metres(depth) == 0;
}

}  // namespace rangefill
