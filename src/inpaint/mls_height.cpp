#include "rangefill/inpaint/mls_height.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "rangefill/core/errors.h"

namespace rangefill {

namespace {

// Per known pixel of a ring: the 15 monomials of degree ≤ 4 in its (u, v), in the order 1, u, v,
// u², v², uv, u³, u²v, uv², v³, u⁴, u³v, u²v², uv³, v⁴ (every entry of b·bᵀ, b = eq. 4's column
// (1, u, v, u², v², uv), is one of them), then its value f times each entry of b.
constexpr int kMoments = 15;
constexpr int kTerms = kMoments + 6;
// Stored with zeros up to a multiple of 4, so that the sums run in whole AVX2 vectors of doubles.
constexpr int kStoredTerms = (kTerms + 3) / 4 * 4;
using Terms = std::array<double, kStoredTerms>;

// kProduct[j][k]: the moment that is b_j·b_k.
constexpr int kProduct[6][6] = {{0, 1, 2, 3, 4, 5},    {1, 3, 5, 6, 8, 7},
                                {2, 5, 4, 7, 9, 8},    {3, 6, 7, 10, 12, 11},
                                {4, 8, 9, 12, 14, 13}, {5, 7, 8, 11, 13, 12}};

// A normal matrix whose reciprocal condition number is below this is ill-conditioned.
constexpr double kMinRcond = 1e-10;
// Ring pixels whose exp(−α·d²) is below e^−28 ≈ 10⁻¹² of the nearest one's are left out: together
// they change no fit by more than rounding does.
constexpr double kNegligibleExponent = 28;
// Beyond α·d² = 600, exp(−α·d²) comes near the smallest double.
constexpr double kLargestExponent = 600;
constexpr int kTile = 8;  // pixels

struct RingPixel {
  int row = 0, col = 0;
  Terms terms{};
};

struct Tile {
  int begin = 0, end = 0;  // of its ring pixels
  cv::Rect box;
};

Eigen::Matrix<double, 6, 1> basis(double u, double v) {
  Eigen::Matrix<double, 6, 1> b;
  b << 1, u, v, u * u, v * v, u * v;  // eq. 2
  return b;
}

Terms terms_of(double u, double v, double f) {
  const double u2 = u * u, v2 = v * v;
  Terms t = {1,      u,      v,       u2,         v2,      u * v,      u2 * u, u2 * v,
             u * v2, v2 * v, u2 * u2, u2 * u * v, u2 * v2, u * v2 * v, v2 * v2};
  const Eigen::Matrix<double, 6, 1> b = basis(u, v);
  for (int k = 0; k < 6; ++k) t[kMoments + k] = f * b[k];
  return t;
}

// One hole of the mask: its pixels and its ring, in row-major order.
struct Hole {
  std::vector<cv::Point> pixels;
  std::vector<cv::Point> ring;
  cv::Rect box;  // of pixels and ring
};

// Solves the first n rows of the weighted normal equations (B·W·Bᵀ)·a = B·W·f (eq. 7) from summed
// terms; false when they are ill-conditioned.
template <int n>
bool solve(const Terms& sum, Eigen::Matrix<double, 6, 1>& a) {
  Eigen::Matrix<double, n, n> normal;
  Eigen::Matrix<double, n, 1> rhs;
  for (int j = 0; j < n; ++j) {
    rhs[j] = sum[kMoments + j];
    for (int k = 0; k < n; ++k) normal(j, k) = sum[kProduct[j][k]];
  }
  const Eigen::LDLT<Eigen::Matrix<double, n, n>> ldlt(normal);
  if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > kMinRcond)) return false;
  a.setZero();
  a.template head<n>() = ldlt.solve(rhs);
  return a.allFinite();
}

// s(p) from the summed terms of eq. 7: the quadratic, else the plane, else the weighted mean.
double evaluate(const Terms& sum, double u, double v) {
  Eigen::Matrix<double, 6, 1> a;
  if (!solve<6>(sum, a) && !solve<3>(sum, a)) {
    a.setZero();
    a[0] = sum[kMoments] / sum[0];
  }
  return basis(u, v).dot(a);
}

// Adds w·terms of the ring pixels [first, last) to `sum`, w = weight[|dr|·width + |dc|] for the
// offset (dr, dc) of each from p. The hot loop: cloned for AVX2 where the processor has it, with
// the same operations in the same order (no fused multiply-add), so that results do not depend
// on the clone.
__attribute__((target_clones("avx2", "default"))) void accumulate(const RingPixel* first,
                                                                  const RingPixel* last,
                                                                  cv::Point p, const double* weight,
                                                                  int width, Terms& sum) {
  Terms total = sum;  // a local copy the compiler can keep in registers
  for (const RingPixel* r = first; r != last; ++r) {
    const double w =
        weight[static_cast<size_t>(std::abs(r->row - p.y)) * width + std::abs(r->col - p.x)];
    for (int k = 0; k < kStoredTerms; ++k) total[k] += w * r->terms[k];
  }
  sum = total;
}

// Eq. 7 at every pixel of the hole. (u, v) = ((col, row) − centre) / scale, the ring's centroid
// and RMS radius, keep the 6×6 systems well-conditioned at any size; the fit does not depend on
// them.
void fill_image_hole(const cv::Mat& depth, const Hole& hole, double alpha, cv::Mat& result) {
  cv::Point2d centre(0, 0);
  for (const cv::Point& p : hole.ring) centre += cv::Point2d(p);
  centre /= static_cast<double>(hole.ring.size());
  double spread = 0;
  for (const cv::Point& p : hole.ring) {
    const cv::Point2d d = cv::Point2d(p) - centre;
    spread += d.dot(d);
  }
  const double scale = std::max(1.0, std::sqrt(spread / hole.ring.size()));
  auto uv = [&](const cv::Point& p) {
    return cv::Point2d((p.x - centre.x) / scale, (p.y - centre.y) / scale);
  };

  // The ring by tiles of kTile² pixels, so that tiles too far to weigh can be skipped whole.
  const cv::Point origin = hole.box.tl();
  const int tiles_across = (hole.box.width + kTile - 1) / kTile;
  const int tiles_down = (hole.box.height + kTile - 1) / kTile;
  std::vector<std::vector<cv::Point>> by_tile(static_cast<size_t>(tiles_across) * tiles_down);
  for (const cv::Point& p : hole.ring) {
    const cv::Point local = p - origin;
    by_tile[(local.y / kTile) * tiles_across + local.x / kTile].push_back(p);
  }
  std::vector<RingPixel> ring;
  ring.reserve(hole.ring.size());
  std::vector<Tile> tiles;
  for (const std::vector<cv::Point>& pixels : by_tile) {
    if (pixels.empty()) continue;
    Tile tile{static_cast<int>(ring.size()), 0, cv::boundingRect(pixels)};
    for (const cv::Point& p : pixels) {
      const cv::Point2d q = uv(p);
      ring.push_back({p.y, p.x, terms_of(q.x, q.y, depth.at<float>(p))});
    }
    tile.end = static_cast<int>(ring.size());
    tiles.push_back(tile);
  }

  // The exact distance from every pixel of the box to the nearest pixel of this ring.
  cv::Mat not_ring(hole.box.size(), CV_8U, cv::Scalar(255)), nearest;
  for (const cv::Point& p : hole.ring) not_ring.at<std::uint8_t>(p - origin) = 0;
  cv::distanceTransform(not_ring, nearest, cv::DIST_L2, cv::DIST_MASK_PRECISE);

  // Eq. 6 for every pixel offset within the box: w(dr, dc) = exp(−α·d²) / d², d² = dr² + dc².
  const int width = hole.box.width;
  std::vector<double> weight(static_cast<size_t>(hole.box.height) * width, 0.0);
  for (int dr = 0; dr < hole.box.height; ++dr) {
    for (int dc = 0; dc < width; ++dc) {
      const double d2 = static_cast<double>(dr) * dr + static_cast<double>(dc) * dc;
      if (d2 > 0) weight[static_cast<size_t>(dr) * width + dc] = std::exp(-alpha * d2) / d2;
    }
  }

  for (const cv::Point& p : hole.pixels) {
    const double closest = std::round(std::pow(nearest.at<float>(p - origin), 2.0f));
    // Far from the ring exp(−α·d²) underflows: the weights are then divided by exp(−α·d_min²)
    // (eq. 7 does not change when all weights are scaled alike) and computed one by one.
    const bool rescale = alpha * closest > kLargestExponent;
    Terms sum{};
    for (const Tile& tile : tiles) {
      const int dx = std::max({0, tile.box.x - p.x, p.x - (tile.box.x + tile.box.width - 1)});
      const int dy = std::max({0, tile.box.y - p.y, p.y - (tile.box.y + tile.box.height - 1)});
      if (alpha * (static_cast<double>(dx) * dx + static_cast<double>(dy) * dy - closest) >
          kNegligibleExponent) {
        continue;
      }
      if (!rescale) {
        accumulate(&ring[tile.begin], &ring[tile.end], p, weight.data(), width, sum);
        continue;
      }
      for (int i = tile.begin; i < tile.end; ++i) {
        const RingPixel& r = ring[i];
        const double dr = r.row - p.y, dc = r.col - p.x;
        const double d2 = dr * dr + dc * dc;
        const double w = std::exp(-alpha * (d2 - closest)) / d2;
        for (int k = 0; k < kTerms; ++k) sum[k] += w * r.terms[k];
      }
    }
    const cv::Point2d q = uv(p);
    result.at<float>(p) = static_cast<float>(evaluate(sum, q.x, q.y));
  }
}

// The holes of the mask (8-connected) and their rings: the finite known pixels within `ring` pixels
// of a hole, each given to its nearest hole.
std::vector<Hole> find_holes(const cv::Mat& depth, const cv::Mat& mask, double ring) {
  cv::Mat distance, labels;
  cv::distanceTransform(mask == 0, distance, labels, cv::DIST_L2, cv::DIST_MASK_5,
                        cv::DIST_LABEL_CCOMP);
  double highest = 0;
  cv::minMaxLoc(labels, nullptr, &highest);
  std::vector<Hole> holes(static_cast<size_t>(highest) + 1);
  for (int row = 0; row < mask.rows; ++row) {
    for (int col = 0; col < mask.cols; ++col) {
      Hole& hole = holes[labels.at<int>(row, col)];
      if (mask.at<std::uint8_t>(row, col)) {
        hole.pixels.emplace_back(col, row);
      } else if (distance.at<float>(row, col) <= ring && std::isfinite(depth.at<float>(row, col))) {
        hole.ring.emplace_back(col, row);
      } else {
        continue;
      }
      const cv::Rect pixel(col, row, 1, 1);
      hole.box = hole.box.empty() ? pixel : (hole.box | pixel);
    }
  }
  return holes;
}

}  // namespace

MlsHeightInpainter::MlsHeightInpainter(const MlsHeightOptions& options)
    : alpha_(options.alpha), ring_(options.ring) {
  if (!(std::isfinite(alpha_) && alpha_ >= 0)) {
    throw InvalidInput("mls: alpha must be finite and non-negative");
  }
  if (!(ring_ >= 1)) throw InvalidInput("mls: the ring must be at least 1 pixel wide");
}

void MlsHeightInpainter::inpaint(cv::InputArray depth_in, cv::InputArray mask_in,
                                 cv::OutputArray out) const {
  const int masked = start_inpainting(depth_in, mask_in, out, name());
  if (masked == 0 || masked == static_cast<int>(mask_in.total())) return;
  const cv::Mat depth = depth_in.getMat(), mask = mask_in.getMat();
  cv::Mat result = out.getMat();
  for (const Hole& hole : find_holes(depth, mask, ring_)) {
    if (hole.pixels.empty()) continue;
    if (hole.ring.empty()) {
      // Only when its neighbours hold no finite value: nothing to fit.
      for (const cv::Point& p : hole.pixels) result.at<float>(p) = 0;
      continue;
    }
    fill_image_hole(depth, hole, alpha_, result);
  }
}

}  // namespace rangefill
