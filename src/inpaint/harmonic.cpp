#include "rangefill/inpaint/harmonic.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "rangefill/core/errors.h"

namespace rangefill {

LaplaceSystem laplace_system(const cv::Mat& values, const cv::Mat& mask) {
  CV_Assert(values.type() == CV_64FC1 && mask.type() == CV_8UC1 && mask.size() == values.size());
  const int rows = values.rows, cols = values.cols;
  cv::Mat index(values.size(), CV_32S, cv::Scalar(-1));
  int unknowns = 0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (mask.at<std::uint8_t>(r, c)) index.at<int>(r, c) = unknowns++;
    }
  }
  std::vector<Eigen::Triplet<double>> entries;
  LaplaceSystem system{Eigen::SparseMatrix<double>(unknowns, unknowns),
                       Eigen::VectorXd::Zero(unknowns)};
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
          system.rhs[i] += values.at<double>(nr, nc);
        } else {
          entries.emplace_back(i, j, -1.0);
        }
      }
      entries.emplace_back(i, i, static_cast<double>(degree));
    }
  }
  system.matrix.setFromTriplets(entries.begin(), entries.end());
  return system;
}

void HarmonicInpainter::inpaint(cv::InputArray depth_in, cv::InputArray mask_in,
                                cv::OutputArray out) const {
  const int masked = start_inpainting(depth_in, mask_in, out, name());
  // With the border free, every masked area reaches a known pixel unless all are masked.
  if (masked == 0 || masked == static_cast<int>(mask_in.total())) return;
  const cv::Mat mask = mask_in.getMat();
  cv::Mat depth;
  depth_in.getMat().convertTo(depth, CV_64F);
  const LaplaceSystem system = laplace_system(depth, mask);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(system.matrix);
  if (solver.info() != Eigen::Success) {
    throw ProcessingError("harmonic: the Laplace system could not be factorised");
  }
  const Eigen::VectorXd solution = solver.solve(system.rhs);
  std::vector<cv::Point> unknowns;  // row-major, the order of the system
  cv::findNonZero(mask, unknowns);
  cv::Mat result = out.getMat();
  for (size_t i = 0; i < unknowns.size(); ++i) {
    result.at<float>(unknowns[i]) = static_cast<float>(solution[i]);
  }
}

}  // namespace rangefill
