#include "rangefill/eval/sensor_holes.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <random>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "rangefill/core/depth_image.h"

namespace rangefill {

namespace {

// Draws from `random` with nothing left to the standard library's distributions, so that the holes
// are the same everywhere.
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : random_(seed) {}
  int between(int lo, int hi) {  // uniform in [lo, hi]
    return lo + static_cast<int>(random_() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  std::uint64_t bits() { return random_(); }

 private:
  std::mt19937_64 random_;
};

}  // namespace

namespace {

// Punches the three kinds of holes into the valid pixels of z (metres), in turn, up to a third of
// the budget each (the rest left to blobs).
class HolePuncher {
 public:
  HolePuncher(const cv::Mat& z, const SensorHoleOptions& options)
      : z_(z), options_(options), punched_(cv::Mat::zeros(z.size(), CV_8U)), draw_(options.seed) {
    cv::findNonZero(z > 0, valid_);
    budget_ = std::llround(options.fraction * static_cast<double>(valid_.size()));
  }

  cv::Mat punch_all() {
    if (valid_.empty() || budget_ <= 0) return punched_;
    shadows();
    dropouts();
    blobs();
    return punched_;
  }

 private:
  static constexpr int kAttempts = 1000;  // per kind of hole

  void punch(cv::Point p) {
    std::uint8_t& pixel = punched_.at<std::uint8_t>(p);
    if (pixel) return;
    pixel = 255;
    ++count_;
  }
  float depth_at(cv::Point p) const {
    return cv::Rect(0, 0, z_.cols, z_.rows).contains(p) ? z_.at<float>(p) : 0.0f;
  }
  bool same(float a, float b) const { return same_surface(a, b, options_.discontinuity); }

  // Bands to the left of a near surface, from the far pixels with a near right neighbour.
  void shadows() {
    const cv::Point left(-1, 0);
    std::vector<cv::Point> edges;
    for (const cv::Point& p : valid_) {
      const float near_depth = depth_at(p - left);
      if (near_depth > 0 && !same(near_depth, z_.at<float>(p)) && z_.at<float>(p) > near_depth) {
        edges.push_back(p);
      }
    }
    for (int attempt = 0; !edges.empty() && count_ < budget_ / 3 && attempt < kAttempts;
         ++attempt) {
      const cv::Point seed = edges[draw_.bits() % edges.size()];
      const double half_length = draw_.between(10, 60) / 2.0;
      for (const cv::Point& edge : edges) {
        if (cv::norm(edge - seed) > half_length) continue;
        // The width the projector cannot see: the disparity between the two surfaces, at least 1.
        const double width = std::max(
            1.0, options_.disparity_scale * (1 / depth_at(edge - left) - 1 / depth_at(edge)));
        for (cv::Point p = edge; p.x > edge.x - width; p += left) {
          if (p != edge && !(depth_at(p) > 0 && same(depth_at(p), depth_at(p - left)))) break;
          punch(p);
        }
      }
    }
  }

  // Random growth (random priorities) over neighbours on the same surface.
  void dropouts() {
    for (int attempt = 0; count_ < 2 * budget_ / 3 && attempt < kAttempts; ++attempt) {
      const int size = draw_.between(50, 600);
      using Entry = std::pair<std::uint64_t, int>;  // priority, pixel index
      std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> front;
      cv::Mat seen = cv::Mat::zeros(z_.size(), CV_8U);
      const cv::Point start = valid_[draw_.bits() % valid_.size()];
      front.emplace(draw_.bits(), start.y * z_.cols + start.x);
      seen.at<std::uint8_t>(start) = 1;
      for (int grown = 0; grown < size && !front.empty(); ++grown) {
        const cv::Point p(front.top().second % z_.cols, front.top().second / z_.cols);
        front.pop();
        punch(p);
        for (const cv::Point& d :
             {cv::Point(1, 0), cv::Point(-1, 0), cv::Point(0, 1), cv::Point(0, -1)}) {
          const cv::Point q = p + d;
          if (!(depth_at(q) > 0) || seen.at<std::uint8_t>(q) ||
              !same(depth_at(q), z_.at<float>(p))) {
            continue;
          }
          seen.at<std::uint8_t>(q) = 1;
          front.emplace(draw_.bits(), q.y * z_.cols + q.x);
        }
      }
    }
  }

  // Ellipses, on the valid pixels they cover.
  void blobs() {
    const int reach = 10;  // the largest semi-axis
    cv::Mat blob(2 * reach + 1, 2 * reach + 1, CV_8U);
    for (int attempt = 0; count_ < budget_ && attempt < kAttempts; ++attempt) {
      const cv::Point centre = valid_[draw_.bits() % valid_.size()];
      const cv::Size axes(draw_.between(2, reach), draw_.between(2, reach));
      const int angle = draw_.between(0, 179);
      blob.setTo(0);
      cv::ellipse(blob, {reach, reach}, axes, angle, 0, 360, cv::Scalar(255), cv::FILLED);
      for (int row = 0; row < blob.rows; ++row) {
        for (int col = 0; col < blob.cols; ++col) {
          const cv::Point p = centre + cv::Point(col - reach, row - reach);
          if (blob.at<std::uint8_t>(row, col) && depth_at(p) > 0) punch(p);
        }
      }
    }
  }

  const cv::Mat& z_;
  const SensorHoleOptions& options_;
  cv::Mat punched_;
  Draw draw_;
  std::vector<cv::Point> valid_;
  long long budget_ = 0, count_ = 0;
};

}  // namespace

cv::Mat punch_depth_holes(cv::InputArray depth_in, const SensorHoleOptions& options) {
  check_depth_type(depth_in.type(), "punch_depth_holes");
  const cv::Mat z = depth_in_metres(depth_in);
  return HolePuncher(z, options).punch_all();
}

}  // namespace rangefill
