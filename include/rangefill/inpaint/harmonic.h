// "harmonic": the membrane fill. The masked pixels solve Laplace's equation (each is the mean of
// its 4-neighbours) with the known pixels as Dirichlet data; the image border is a free (Neumann)
// edge. A sparse SPD system, solved exactly (Eigen's SimplicialLDLT, in nested-dissection order).
// An image with every pixel masked gives nothing to go by and comes back 0. Given a guide image
// (a registered colour image), each pixel is its 4-neighbours' mean weighed by how alike they look
// in it, so that the membrane bends where the guide has an edge.
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "rangefill/inpaint/inpainter.h"

namespace rangefill {

/// exp(−‖a − b‖² / (2 sigma²)), at least 1e-3 (no neighbour weighs nothing): how alike two pixels
/// of a guide image look, the range weight of a joint-bilateral filter.
inline float guide_affinity(const cv::Vec3f& a, const cv::Vec3f& b, float sigma) {
  const cv::Vec3f d = a - b;
  return std::max(std::exp(-d.dot(d) / (2 * sigma * sigma)), 1e-3F);
}

class HarmonicInpainter : public Inpainter {
 public:
  HarmonicInpainter() = default;
  /// Guided by `guide` (CV_32FC3, the size of the images to inpaint): the edge between two
  /// neighbours weighs guide_affinity(their guide colours, sigma). Throws InvalidInput on another
  /// type or a sigma not above 0.
  HarmonicInpainter(cv::Mat guide, float sigma);
  std::string name() const override { return "harmonic"; }
  void inpaint(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out) const override;
  std::unique_ptr<Inpainter> guided(const cv::Mat& guide, float sigma) const override {
    return std::make_unique<HarmonicInpainter>(guide, sigma);
  }

 private:
  cv::Mat guide_;
  float sigma_ = 0;
};

/// The discrete Laplace problem of the harmonic fill: L u = b over the pixels of `mask` (CV_8U,
/// non-zero = unknown) in row-major order, L the 5-point Laplacian (degree on the diagonal, −1 to
/// each masked 4-neighbour; the image border free) and b the sum of each pixel's known
/// 4-neighbours in `values` (CV_64F). With a `guide` (CV_32FC3, empty for none) each edge weighs
/// guide_affinity(…, sigma) instead of 1: the weighted graph Laplacian. L is SPD when some pixel
/// is known.
struct LaplaceSystem {
  Eigen::SparseMatrix<double> matrix;
  Eigen::VectorXd rhs;
};
LaplaceSystem laplace_system(const cv::Mat& values, const cv::Mat& mask,
                             const cv::Mat& guide = cv::Mat(), float sigma = 0);

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
