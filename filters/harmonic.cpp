#include "harmonic.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "rangefill/errors.h"

namespace rangefill {

void HarmonicInpainter::inpaint(cv::InputArray depth_in, cv::InputArray mask_in,
                                cv::OutputArray out) const {
  const int masked = start_inpainting(depth_in, mask_in, out, name());
  // With the border free, every masked area reaches a known pixel unless all are masked.
  if (masked == 0 || masked == static_cast<int>(mask_in.total())) return;
  const cv::Mat depth = depth_in.getMat(), mask = mask_in.getMat();
  cv::Mat result = out.getMat();
  const int rows = depth.rows, cols = depth.cols;

  // Unknowns: the masked pixels, numbered in row-major order.
  cv::Mat index(depth.size(), CV_32S, cv::Scalar(-1));
  int unknowns = 0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (mask.at<std::uint8_t>(r, c)) index.at<int>(r, c) = unknowns++;
    }
  }

  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(unknowns);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const int i = index.at<int>(r, c);
      if (i < 0) continue;
      int degree = 0;
      const int neighbours[4][2] = {{r - 1, c}, {r + 1, c}, {r, c - 1}, {r, c + 1}};
      for (const auto& [nr, nc] : neighbours) {
        if (nr < 0 || nr >= rows || nc < 0 || nc >= cols) continue;
        ++degree;
        const int j = index.at<int>(nr, nc);
        if (j < 0) {
          rhs[i] += depth.at<float>(nr, nc);
        } else {
          entries.emplace_back(i, j, -1.0);
        }
      }
      entries.emplace_back(i, i, static_cast<double>(degree));
    }
  }
  Eigen::SparseMatrix<double> laplacian(unknowns, unknowns);
  laplacian.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(laplacian);
  if (solver.info() != Eigen::Success) {
    throw ProcessingError("harmonic: the Laplace system could not be factorised");
  }
  const Eigen::VectorXd solution = solver.solve(rhs);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const int i = index.at<int>(r, c);
      if (i >= 0) result.at<float>(r, c) = static_cast<float>(solution[i]);
    }
  }
}

}  // namespace rangefill
