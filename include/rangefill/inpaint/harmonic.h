// "harmonic": the membrane fill. The masked pixels solve Laplace's equation (each is the mean of
// its 4-neighbours) with the known pixels as Dirichlet data; the image border is a free (Neumann)
// edge. A sparse SPD system, solved exactly (Eigen's SimplicialLDLT, in nested-dissection order).
// An image with every pixel masked gives nothing to go by and comes back 0.
#pragma once

#include <Eigen/SparseCholesky>
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

/// The matrix of laplace_system(values, mask) factorised (LDLᵀ), its pixels eliminated in
/// nested-dissection order (George 1973: the region's bounding box cut in two across its longer
/// side, each half so in turn, the pixels on the cut last): O(n log n) fill and O(n^1.5) work for
/// a grid, found in O(n log n), where Eigen's minimum-degree ordering alone takes longer than the
/// factorisation. Throws ProcessingError when the matrix is not SPD.
class LaplaceFactor {
 public:
  LaplaceFactor(const Eigen::SparseMatrix<double>& matrix, const cv::Mat& mask);
  /// L⁻¹ b, b and the result in the system's (row-major) order.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

 private:
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order_;  // row-major → elimination
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>>
      ldlt_;
};

}  // namespace rangefill
