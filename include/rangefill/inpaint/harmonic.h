// "harmonic": the membrane fill. The masked pixels solve Laplace's equation (each is the mean of
// its 4-neighbours) with the known pixels as Dirichlet data; the image border is a free (Neumann)
// edge. A sparse SPD system, solved exactly (Eigen's SimplicialLDLT). An image with every pixel
// masked gives nothing to go by and comes back 0.
#pragma once

#include <Eigen/SparseCore>

#include "rangefill/inpaint/inpainter.h"

namespace rangefill {

class HarmonicInpainter : public Inpainter {
 public:
  std::string name() const override { return "harmonic"; }
  void inpaint(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out) const override;
};

/// The discrete Laplace problem of the harmonic fill: L u = b over the pixels of `mask` (CV_8U,
/// non-zero = unknown) in row-major order, L the 5-point Laplacian (degree on the diagonal, −1 to
/// each masked 4-neighbour; the image border free) and b the sum of each pixel's known
/// 4-neighbours in `values` (CV_64F). L is SPD when some pixel is known.
struct LaplaceSystem {
  Eigen::SparseMatrix<double> matrix;
  Eigen::VectorXd rhs;
};
LaplaceSystem laplace_system(const cv::Mat& values, const cv::Mat& mask);

}  // namespace rangefill
