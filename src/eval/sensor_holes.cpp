#include "rangefill/eval/sensor_holes.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <random>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "rangefill/depth/depth_image.h"

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

cv::Mat punch_depth_holes(cv::InputArray depth_in, const SensorHoleOptions& options) {
  check_depth_type(depth_in.type(), "punch_depth_holes");
  const cv::Mat z = depth_in_metres(depth_in);
  const cv::Rect image(0, 0, z.cols, z.rows);
  std::vector<cv::Point> valid;
  cv::findNonZero(z > 0, valid);
  cv::Mat punched = cv::Mat::zeros(z.size(), CV_8U);
  const long long budget = std::llround(options.fraction * static_cast<double>(valid.size()));
  if (valid.empty() || budget <= 0) return punched;
  long long count = 0;
  const auto punch = [&](cv::Point p) {
    std::uint8_t& pixel = punched.at<std::uint8_t>(p);
    if (pixel) return;
    pixel = 255;
    ++count;
  };
  const auto depth_at = [&](cv::Point p) { return image.contains(p) ? z.at<float>(p) : 0.0f; };
  Draw draw(options.seed);
  const int attempts = 1000;  // per kind of hole

  // Shadows: bands to the left of a near surface, from the far pixels with a near right neighbour.
  const cv::Point left(-1, 0);
  std::vector<cv::Point> edges;
  for (const cv::Point& p : valid) {
    const float near_depth = depth_at(p - left);
    if (near_depth > 0 && !same_surface(near_depth, z.at<float>(p), options.discontinuity) &&
        z.at<float>(p) > near_depth) {
      edges.push_back(p);
    }
  }
  for (int attempt = 0; !edges.empty() && count < budget / 3 && attempt < attempts; ++attempt) {
    const cv::Point seed = edges[draw.bits() % edges.size()];
    const double half_length = draw.between(10, 60) / 2.0;
    for (const cv::Point& edge : edges) {
      if (cv::norm(edge - seed) > half_length) continue;
      // The width the projector cannot see: the disparity between the two surfaces, at least 1.
      const double width =
          std::max(1.0, options.disparity_scale * (1 / depth_at(edge - left) - 1 / depth_at(edge)));
      for (cv::Point p = edge; p.x > edge.x - width; p += left) {
        if (p != edge && !(depth_at(p) > 0 &&
                           same_surface(depth_at(p), depth_at(p - left), options.discontinuity))) {
          break;
        }
        punch(p);
      }
    }
  }

  // Dropouts: random growth (random priorities) over neighbours on the same surface.
  for (int attempt = 0; count < 2 * budget / 3 && attempt < attempts; ++attempt) {
    const int size = draw.between(50, 600);
    using Entry = std::pair<std::uint64_t, int>;  // priority, pixel index
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> front;
    cv::Mat seen = cv::Mat::zeros(z.size(), CV_8U);
    const cv::Point start = valid[draw.bits() % valid.size()];
    front.emplace(draw.bits(), start.y * z.cols + start.x);
    seen.at<std::uint8_t>(start) = 1;
    for (int grown = 0; grown < size && !front.empty(); ++grown) {
      const cv::Point p(front.top().second % z.cols, front.top().second / z.cols);
      front.pop();
      punch(p);
      for (const cv::Point& d :
           {cv::Point(1, 0), cv::Point(-1, 0), cv::Point(0, 1), cv::Point(0, -1)}) {
        const cv::Point q = p + d;
        if (!(depth_at(q) > 0) || seen.at<std::uint8_t>(q) ||
            !same_surface(depth_at(q), z.at<float>(p), options.discontinuity)) {
          continue;
        }
        seen.at<std::uint8_t>(q) = 1;
        front.emplace(draw.bits(), q.y * z.cols + q.x);
      }
    }
  }

  // Blobs: ellipses, on the valid pixels they cover.
  const int reach = 10;  // the largest semi-axis
  cv::Mat blob(2 * reach + 1, 2 * reach + 1, CV_8U);
  for (int attempt = 0; count < budget && attempt < attempts; ++attempt) {
    const cv::Point centre = valid[draw.bits() % valid.size()];
    const cv::Size axes(draw.between(2, reach), draw.between(2, reach));
    const int angle = draw.between(0, 179);
    blob.setTo(0);
    cv::ellipse(blob, {reach, reach}, axes, angle, 0, 360, cv::Scalar(255), cv::FILLED);
    for (int row = 0; row < blob.rows; ++row) {
      for (int col = 0; col < blob.cols; ++col) {
        const cv::Point p = centre + cv::Point(col - reach, row - reach);
        if (blob.at<std::uint8_t>(row, col) && depth_at(p) > 0) punch(p);
      }
    }
  }
  return punched;
}

}  // namespace rangefill
