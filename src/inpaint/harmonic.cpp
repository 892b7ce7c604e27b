#include "rangefill/inpaint/harmonic.h"

#include <algorithm>
#include <utility>

#include <Eigen/Sparse>

#include "rangefill/core/errors.h"

namespace rangefill {

LaplaceSystem laplace_system(const cv::Mat& values, const cv::Mat& mask, const cv::Mat& guide,
                             float sigma) {
  CV_Assert(values.type() == CV_64FC1 && mask.type() == CV_8UC1 && mask.size() == values.size());
  CV_Assert(guide.empty() || (guide.type() == CV_32FC3 && guide.size() == values.size()));
  const auto weight = [&](int r, int c, int nr, int nc) {
    return guide.empty() ? 1.0
                         : static_cast<double>(guide_affinity(guide.at<cv::Vec3f>(r, c),
                                                              guide.at<cv::Vec3f>(nr, nc), sigma));
  };
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
      double degree = 0;
      const int neighbours[4][2] = {{r - 1, c}, {r + 1, c}, {r, c - 1}, {r, c + 1}};
      for (const auto& [nr, nc] : neighbours) {
        if (nr < 0 || nr >= rows || nc < 0 || nc >= cols) continue;
        const double w = weight(r, c, nr, nc);
        degree += w;
        const int j = index.at<int>(nr, nc);
        if (j < 0) {
          system.rhs[i] += w * values.at<double>(nr, nc);
        } else {
          entries.emplace_back(i, j, -w);
        }
      }
      entries.emplace_back(i, i, degree);
    }
  }
  system.matrix.setFromTriplets(entries.begin(), entries.end());
  return system;
}

namespace {

// Places the pixels of points[begin, end) in nested-dissection order: the pixels on the cut (the
// middle column of their bounding box when it is wider than tall, else its middle row) after the
// two halves it parts, between which no pixel has a 4-neighbour.
void order_by_dissection(std::vector<cv::Point>& points, size_t begin, size_t end) {
  constexpr size_t kSmallest = 16;  // a part this small keeps row-major order
  if (end - begin <= kSmallest) return;
  const auto first = points.begin() + static_cast<std::ptrdiff_t>(begin);
  const auto last = points.begin() + static_cast<std::ptrdiff_t>(end);
  cv::Point low = *first, high = *first;
  for (auto p = first; p != last; ++p) {
    low = {std::min(low.x, p->x), std::min(low.y, p->y)};
    high = {std::max(high.x, p->x), std::max(high.y, p->y)};
  }
  const bool across_x = high.x - low.x >= high.y - low.y;
  const int cut = across_x ? (low.x + high.x) / 2 : (low.y + high.y) / 2;
  const auto coordinate = [&](const cv::Point& p) { return across_x ? p.x : p.y; };
  const auto second_half =
      std::stable_partition(first, last, [&](const cv::Point& p) { return coordinate(p) < cut; });
  const auto on_cut = std::stable_partition(
      second_half, last, [&](const cv::Point& p) { return coordinate(p) > cut; });
  if (second_half == first && on_cut == last) return;  // a line: nothing to cut
  order_by_dissection(points, begin, static_cast<size_t>(second_half - points.begin()));
  order_by_dissection(points, static_cast<size_t>(second_half - points.begin()),
                      static_cast<size_t>(on_cut - points.begin()));
}

}  // namespace

LaplaceFactor::LaplaceFactor(const Eigen::SparseMatrix<double>& matrix, const cv::Mat& mask)
    : order_(static_cast<int>(matrix.rows())) {
  std::vector<cv::Point> points;  // row-major, the order of the system
  cv::findNonZero(mask, points);
  CV_Assert(static_cast<Eigen::Index>(points.size()) == matrix.rows());
  cv::Mat index(mask.size(), CV_32S);
  for (size_t i = 0; i < points.size(); ++i) index.at<int>(points[i]) = static_cast<int>(i);
  order_by_dissection(points, 0, points.size());
  for (size_t k = 0; k < points.size(); ++k) order_.indices()[index.at<int>(points[k])] = k;
  Eigen::SparseMatrix<double> permuted;
  permuted = matrix.twistedBy(order_);
  ldlt_.compute(permuted);
  if (ldlt_.info() != Eigen::Success) {
    throw ProcessingError("the Laplace system could not be factorised");
  }
}

Eigen::VectorXd LaplaceFactor::solve(const Eigen::VectorXd& b) const {
  return order_.transpose() * ldlt_.solve(order_ * b).eval();
}

HarmonicInpainter::HarmonicInpainter(cv::Mat guide, float sigma)
    : guide_(std::move(guide)), sigma_(sigma) {
  if (guide_.type() != CV_32FC3 || !(sigma_ > 0)) {
    throw InvalidInput("harmonic: the guide must be CV_32FC3 and its sigma above 0");
  }
}

void HarmonicInpainter::inpaint(cv::InputArray depth_in, cv::InputArray mask_in,
                                cv::OutputArray out) const {
  const int masked = start_inpainting(depth_in, mask_in, out, name());
  // With the border free, every masked area reaches a known pixel unless all are masked.
  if (masked == 0 || masked == static_cast<int>(mask_in.total())) return;
  const cv::Mat mask = mask_in.getMat();
  cv::Mat depth;
  depth_in.getMat().convertTo(depth, CV_64F);
  if (!guide_.empty() && guide_.size() != mask.size()) {
    throw InvalidInput("harmonic: the guide is not the size of the image");
  }
  const LaplaceSystem system = laplace_system(depth, mask, guide_, sigma_);
  const Eigen::VectorXd solution = LaplaceFactor(system.matrix, mask).solve(system.rhs);
  std::vector<cv::Point> unknowns;  // row-major, the order of the system
  cv::findNonZero(mask, unknowns);
  cv::Mat result = out.getMat();
  for (size_t i = 0; i < unknowns.size(); ++i) {
    result.at<float>(unknowns[i]) = static_cast<float>(solution[i]);
  }
}

}  // namespace rangefill
