// "harmonic": the membrane fill. The masked pixels solve Laplace's equation (each is the mean of
// its 4-neighbours) with the known pixels as Dirichlet data; the image border is a free (Neumann)
// edge. A sparse SPD system, solved exactly (Eigen's SimplicialLDLT). An image with every pixel
// masked gives nothing to go by and comes back 0.
#pragma once

#include "rangefill/inpainter.h"

namespace rangefill {

class HarmonicInpainter : public Inpainter {
 public:
  std::string name() const override { return "harmonic"; }
  void inpaint(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out) const override;
};

}  // namespace rangefill
