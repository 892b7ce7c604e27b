// Inpainting back-ends: restore the masked pixels of a float image from the others. They know
// nothing of meshes, which is what lets the same back-ends serve mesh repair and depth maps. This
// is the interface; inpainters.h makes them by name.
#pragma once

#include <memory>
#include <string>

#include <opencv2/core.hpp>

namespace rangefill {

/// A back-end. inpaint(depth, mask, out): `depth` is CV_32FC1; `mask` is CV_8UC1 of the same size,
/// non-zero at the pixels to restore; every other pixel of `depth` is taken as valid data. `out`
/// receives a CV_32FC1 image equal to `depth` outside the mask. Implementations are stateless once
/// made and may be called from several threads at once.
class Inpainter {
 public:
  virtual ~Inpainter() = default;
  virtual std::string name() const = 0;
  virtual void inpaint(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out) const = 0;
  /// This back-end guided by `guide` (CV_32FC3, a registered colour image the size of the images
  /// it will inpaint): the smoothness between two pixels weakened by their guide_affinity(…,
  /// sigma) (harmonic.h). nullptr when the back-end reads no guide.
  virtual std::unique_ptr<Inpainter> guided(const cv::Mat& guide, float sigma) const;
};

/// Checks the inpaint() preconditions above; throws InvalidInput naming `who` otherwise.
void check_inpaint_arguments(cv::InputArray depth, cv::InputArray mask, const std::string& who);

/// How a back-end's inpaint() starts: checks the arguments (check_inpaint_arguments), sets `out`
/// to a copy of `depth` and returns the number of masked pixels. When every pixel is masked there
/// is nothing to go by: `out` is then set to 0.
int start_inpainting(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out,
                     const std::string& who);

}  // namespace rangefill
