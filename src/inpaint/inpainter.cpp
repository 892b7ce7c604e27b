#include "rangefill/inpaint/inpainter.h"

#include "rangefill/core/errors.h"

namespace rangefill {

std::unique_ptr<Inpainter> Inpainter::guided(const cv::Mat& /*guide*/, float /*sigma*/) const {
  return nullptr;
}

int start_inpainting(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out,
                     const std::string& who) {
  check_inpaint_arguments(depth, mask, who);
  depth.copyTo(out);
  const int masked = cv::countNonZero(mask);
  if (masked == static_cast<int>(mask.total())) out.setTo(0);
  return masked;
}

void check_inpaint_arguments(cv::InputArray depth, cv::InputArray mask, const std::string& who) {
  if (depth.type() != CV_32FC1) throw InvalidInput(who + ": depth must be CV_32FC1");
  if (mask.type() != CV_8UC1) throw InvalidInput(who + ": mask must be CV_8UC1");
  if (depth.size() != mask.size()) {
    throw InvalidInput(who + ": mask size differs from depth size");
  }
}

}  // namespace rangefill
