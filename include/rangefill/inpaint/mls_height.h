// "mls": the moving-least-squares height fit of Wang & Oliveira ("Filling holes on locally smooth
// surfaces reconstructed from point clouds", Sections 3 and 4.4). Every masked pixel p gets the
// value at p of its own quadratic s(u, v) = a0 + a1·u + a2·v + a3·u² + a4·v² + a5·uv (eq. 2),
// fitted by weighted least squares (eq. 5, 7) to the known pixels of a ring around p's hole (their
// vicinity) with the weights w_i(p) = exp(−α·d_i²) / d_i² of eq. 6, d_i the distance from p to
// pixel i in pixels. Each connected hole of the mask (8-connected) is fitted from its own ring:
// the known pixels within `ring` pixels of it that are nearer to it than to any other hole. A fit
// whose 6×6 normal matrix is ill-conditioned falls back to a plane (a0 + a1·u + a2·v), then to the
// weighted mean. Linear in the data and exact on quadratics. An image with every pixel masked gives
// nothing to go by and comes back 0, like `harmonic`.
#pragma once

#include "rangefill/inpaint/inpainter.h"

namespace rangefill {

struct MlsHeightOptions {
  double alpha = 1.0 / 64;  // α of eq. 6, per squared pixel (docs/backends.md)
  double ring = 3;          // known pixels within this many pixels of a hole are fitted
};

class MlsHeightInpainter : public Inpainter {
 public:
  /// Throws InvalidInput unless options.alpha is finite and ≥ 0 and options.ring ≥ 1.
  explicit MlsHeightInpainter(const MlsHeightOptions& options = {});
  std::string name() const override { return "mls"; }
  void inpaint(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out) const override;

 private:
  double alpha_;  // α of eq. 6, per squared pixel
  double ring_;   // pixels
};

}  // namespace rangefill
