#include "rangefill/eval/depth_baselines.h"

#include "core/module_loader.h"
#include "eval/fast_bilateral_solver.h"

namespace rangefill {

cv::Mat fill_depth_fast_bilateral_solver(const cv::Mat& depth, const cv::Mat& color,
                                         const cv::Mat& to_fill) {
  CV_Assert(depth.type() == CV_16UC1 && color.type() == CV_8UC3 && to_fill.type() == CV_8UC1 &&
            color.size() == depth.size() && to_fill.size() == depth.size());
  static const auto solve = reinterpret_cast<fbs::Entry>(module_entry(
      fbs::kModule, fbs::kEntry, reinterpret_cast<const void*>(&fill_depth_fast_bilateral_solver),
      "the fast bilateral solver (OpenCV contrib's ximgproc)"));
  cv::Mat solved;
  solve(depth, color, to_fill, solved);
  cv::Mat filled = depth.clone();
  solved.copyTo(filled, to_fill);
  return filled;
}

}  // namespace rangefill
