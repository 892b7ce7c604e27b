// OpenCV's cv::inpaint back-ends, "telea" (Telea 2004, fast marching) and "ns" (Bertalmío et al.
// 2001, Navier–Stokes), with workarounds for two bugs of OpenCV 4.6 (Debian 12):
//  - opencv/opencv#25404 (fixed in 4.10): INPAINT_TELEA on CV_32F adds a rounding bias of +0.5
//    and a gradient term of up to ±√2 grey levels per pixel, far off for depth in [0, 1]. Telea
//    therefore runs on CV_16U with the known values mapped affinely onto [0, 65535] (error ≤ 2·10⁻⁵
//    of the known range; a constant image comes back exact).
//  - opencv/opencv#25389 (fixed in 4.10): both methods mishandle masked pixels that touch the top
//    or left border. The image is padded with a one-pixel masked ring, inpainted, and cropped.
#pragma once

#include "rangefill/inpaint/inpainter.h"

namespace rangefill {

struct OpenCvInpaintOptions {
  double radius = 5;  // neighbourhood radius in pixels
};

class OpenCvInpainter : public Inpainter {
 public:
  /// `flags` is cv::INPAINT_TELEA or cv::INPAINT_NS.
  OpenCvInpainter(int flags, double radius) : flags_(flags), radius_(radius) {}
  std::string name() const override;
  void inpaint(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out) const override;

 private:
  int flags_;
  double radius_;
};

}  // namespace rangefill
