// What the FoE energy (foe_energy.cpp) and inference (foe_map.cpp) share: cliques as runs along
// rows, correlations with the filters, the energy over a set of cliques, the unknowns and the
// matrices of quadratic forms over them.
#pragma once

#include <vector>

#include <Eigen/Sparse>
#include <opencv2/core.hpp>

#include "rangefill/inpaint/foe_model.h"

namespace rangefill::foe_terms {

// Cliques as runs of filter centres along a row: (row, first column, one past the last).
struct CliqueRun {
  int row, begin, end;
};

// Every clique whose filter lies inside an image of `size` (filters of radius r).
std::vector<CliqueRun> valid_cliques(cv::Size size, int r);

// The valid cliques whose filter covers at least one pixel of `mask` (the others do not change
// when the masked pixels do).
std::vector<CliqueRun> cliques_touching(const cv::Mat& mask, int r);

// y = J ⋆ x at the cliques of `runs`, 0 elsewhere. Plain loops that sum the taps in one order,
// so results are the same at any thread count (cv::filter2D's are not); the inner loops vectorise.
cv::Mat correlate(const cv::Mat& x, const cv::Mat& kernel, const std::vector<CliqueRun>& runs);

// sum += Jᵀ z, z read at the cliques of `runs` only.
void add_correlation_adjoint(const cv::Mat& z, const cv::Mat& kernel,
                             const std::vector<CliqueRun>& runs, cv::Mat& sum);

// The weights w_i of the quadratic forms Σ_c w_ic (J_i ⋆ x)_c² / 2 that inference builds, at every
// clique: pixel-major ([pixel · count + i]), 0 off the cliques.
struct CliqueWeights {
  std::vector<double> half_quadratic;  // α_i / (1 + y²/2): the bound of Geman & Yang
  std::vector<double> curvature;  // α_i ρ''(y) = α_i (1 − y²/2) / (1 + y²/2)²: the Hessian
};

// E over the cliques of `runs` (Roth & Black's eq. for the FoE energy), each clique's terms times
// its `clique_weights` (CV_64F; empty: 1), ∇E into `gradient` and the clique weights at x into
// `weights`.
double energy_over(const FoeModel& model, const cv::Mat& x, const std::vector<CliqueRun>& runs,
                   cv::Mat* gradient, CliqueWeights* weights = nullptr,
                   const cv::Mat& clique_weights = cv::Mat());

// Throws InvalidInput unless x is CV_64FC1.
void check_energy_argument(const cv::Mat& x);

// Asserts that `clique_weights` is empty or CV_64FC1 of x's size.
void check_clique_weights(const cv::Mat& clique_weights, const cv::Mat& x);

// The unknown pixels of `mask` in row-major order, and each one's number (−1 elsewhere).
struct Unknowns {
  explicit Unknowns(const cv::Mat& mask) : index(mask.size(), CV_32S, cv::Scalar(-1)) {
    cv::findNonZero(mask, pixels);
    for (size_t k = 0; k < pixels.size(); ++k) index.at<int>(pixels[k]) = static_cast<int>(k);
  }
  int at(cv::Point p) const {
    return p.x < 0 || p.y < 0 || p.x >= index.cols || p.y >= index.rows ? -1 : index.at<int>(p);
  }
  std::vector<cv::Point> pixels;
  cv::Mat index;  // CV_32S
};

// The matrices A = Σ_i Σ_c w_ic J_ic J_icᵀ over the unknowns that inference factorises. As
// ρ(y) = log(1 + y²/2) has ρ'' ≤ 1, w = α_i bounds E around every point (A is then the Hessian of
// the Gaussian field with the same filters); as ρ is concave in y², the half-quadratic weights
// w = α_i / (1 + y²/2) at the current responses bound it more tightly around the current point
// (Geman & Yang): either way x − A⁻¹∇E lowers E. With w = α_i ρ''(y), A is the Hessian. Entries
// A(p, p + d) = Σ_i Σ_t w_i(p − t) K_i(t) K_i(t + d), with K_i the scaled kernels, over the
// (4r + 1)² offsets d of the stencil.
class FilterMatrix {
 public:
  FilterMatrix(const FoeModel& model, const Unknowns& unknowns) : unknowns_(unknowns) {
    const int r = model.size / 2, count = model.count();
    count_ = count;
    // For each stencil offset d, the taps t with t + d in the kernel and the products
    // K_i(t) K_i(t + d) of every filter.
    for (int dy = -2 * r; dy <= 2 * r; ++dy) {
      for (int dx = -2 * r; dx <= 2 * r; ++dx) {
        Offset offset;
        for (int ty = std::max(-r, -r - dy); ty <= std::min(r, r - dy); ++ty) {
          for (int tx = std::max(-r, -r - dx); tx <= std::min(r, r - dx); ++tx) {
            offset.taps.emplace_back(tx, ty);
            for (int i = 0; i < count; ++i) {
              const double scale = model.input_scale * model.input_scale;
              offset.products.push_back(scale * model.filters[i].at<double>(ty + r, tx + r) *
                                        model.filters[i].at<double>(ty + dy + r, tx + dx + r));
            }
          }
        }
        offsets_.push_back(std::move(offset));
      }
    }
    const int n = static_cast<int>(unknowns.pixels.size()), side = 4 * r + 1;
    std::vector<Eigen::Triplet<double>> pattern;
    for (int column = 0; column < n; ++column) {
      for (int d = 0; d < side * side; ++d) {
        const cv::Point p = unknowns.pixels[column] + cv::Point(d % side - 2 * r, d / side - 2 * r);
        const int row = unknowns.at(p);
        if (row >= column) {  // the lower triangle: A is symmetric
          pattern.emplace_back(row, column, 1.0);
          entry_offsets_.push_back(d);
        }
      }
    }
    matrix_.resize(n, n);
    matrix_.setFromTriplets(pattern.begin(), pattern.end());  // keeps the column-major order
    matrix_.makeCompressed();
  }

  // The lower triangle of A for clique weights (pixel-major, as in CliqueWeights), with `ridge`
  // added to the diagonal.
  const Eigen::SparseMatrix<double>& assemble(const std::vector<double>& weights, double ridge) {
    const int cols = unknowns_.index.cols, rows = unknowns_.index.rows;
    double* values = matrix_.valuePtr();
    const int* starts = matrix_.outerIndexPtr();
    for (int column = 0; column < matrix_.outerSize(); ++column) {
      const cv::Point p = unknowns_.pixels[column];
      for (int k = starts[column]; k < starts[column + 1]; ++k) {
        const Offset& offset = offsets_[entry_offsets_[k]];
        double sum = matrix_.innerIndexPtr()[k] == column ? ridge : 0;
        const double* product = offset.products.data();
        for (const cv::Point& t : offset.taps) {
          const cv::Point centre = p - t;  // of the clique; none outside the image
          if (centre.x >= 0 && centre.y >= 0 && centre.x < cols && centre.y < rows) {
            const double* w = &weights[static_cast<size_t>(centre.y * cols + centre.x) * count_];
            for (int i = 0; i < count_; ++i) sum += w[i] * product[i];
          }
          product += count_;
        }
        values[k] = sum;
      }
    }
    return matrix_;
  }

 private:
  struct Offset {
    std::vector<cv::Point> taps;
    std::vector<double> products;  // [tap · count + filter]
  };
  const Unknowns& unknowns_;
  int count_ = 0;
  std::vector<Offset> offsets_;
  std::vector<int> entry_offsets_;  // the stencil offset of each stored entry
  Eigen::SparseMatrix<double> matrix_;
};

// E, ∇E over the unknowns and the clique weights at a point.
struct Evaluation {
  double energy = 0;
  Eigen::VectorXd gradient;
  CliqueWeights weights;
};

Evaluation evaluate(const FoeModel& model, const cv::Mat& x, const std::vector<CliqueRun>& runs,
                    const Unknowns& unknowns, const cv::Mat& clique_weights = cv::Mat());

// What foe_map and foe_hessian_of_unknowns share: the unknowns, the cliques that see them, and
// the matrices of quadratic forms over them.
struct InferenceProblem {
  InferenceProblem(const FoeModel& model, const cv::Mat& mask)
      : unknowns(mask), runs(cliques_touching(mask, model.size / 2)), matrices(model, unknowns) {}
  Unknowns unknowns;
  std::vector<CliqueRun> runs;
  FilterMatrix matrices;
};

}  // namespace rangefill::foe_terms
