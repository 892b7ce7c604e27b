#include "rangefill/image/range_image.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include <opencv2/imgproc.hpp>

#include "rangefill/core/errors.h"

namespace rangefill {

cv::Mat RangeImage::mask() const {
  return labels == kHolePixel;
}

Vec3 RangeImage::local_point(int row, int col, double value) const {
  return {x_min + col * step, y_max - row * step, value / depth_scale + depth_offset};  // eq. 13
}

namespace {

// Labels the pixels whose centres lie inside the polygon (even-odd rule) as hole pixels.
void label_polygon_interior(const std::vector<Vec2>& polygon, RangeImage& image) {
  std::vector<double> crossings;
  for (int row = 0; row < image.labels.rows; ++row) {
    const double y = image.y_max - row * image.step;
    crossings.clear();
    for (size_t i = 0; i < polygon.size(); ++i) {
      const Vec2& a = polygon[i];
      const Vec2& b = polygon[(i + 1) % polygon.size()];
      if ((a.y() > y) != (b.y() > y)) {
        crossings.push_back(a.x() + (y - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
      }
    }
    std::sort(crossings.begin(), crossings.end());
    for (size_t i = 0; i + 1 < crossings.size(); i += 2) {
      const int first =
          std::max(0, static_cast<int>(std::ceil((crossings[i] - image.x_min) / image.step)));
      const int last =
          std::min(image.labels.cols - 1,
                   static_cast<int>(std::ceil((crossings[i + 1] - image.x_min) / image.step)) - 1);
      for (int col = first; col <= last; ++col)
        image.labels.at<std::uint8_t>(row, col) = kHolePixel;
    }
  }
}

// Empty pixels 4-connected to the image border are outside the zone; the others are gaps.
void label_outside(RangeImage& image) {
  cv::Mat& labels = image.labels;
  std::vector<cv::Point> stack;
  auto seed = [&](int row, int col) {
    if (labels.at<std::uint8_t>(row, col) == kGapPixel) {
      labels.at<std::uint8_t>(row, col) = kOutsidePixel;
      stack.emplace_back(col, row);
    }
  };
  for (int col = 0; col < labels.cols; ++col) {
    seed(0, col);
    seed(labels.rows - 1, col);
  }
  for (int row = 0; row < labels.rows; ++row) {
    seed(row, 0);
    seed(row, labels.cols - 1);
  }
  while (!stack.empty()) {
    const cv::Point p = stack.back();
    stack.pop_back();
    if (p.x > 0) seed(p.y, p.x - 1);
    if (p.x + 1 < labels.cols) seed(p.y, p.x + 1);
    if (p.y > 0) seed(p.y - 1, p.x);
    if (p.y + 1 < labels.rows) seed(p.y + 1, p.x);
  }
}

// Z-buffers `face` into `depth` (and its colours into `color`, when the mesh has them) at the
// pixel centres of `image`'s grid inside its projection; faces seen from behind or edge-on draw
// nothing. The surface nearest the viewer (largest local z) wins.
void rasterize_face(const Mesh& mesh, int face, const RangeImage& image, cv::Mat_<double>& depth,
                    cv::Mat_<cv::Vec3f>& color) {
  const double q = image.step;
  const cv::Size size = depth.size();
  const Frame& frame = image.plane.frame;
  Vec3 corners[3];
  for (int k = 0; k < 3; ++k) corners[k] = frame.to_local(mesh.positions[mesh.triangles[face][k]]);
  const Vec3 ab = corners[1] - corners[0], ac = corners[2] - corners[0];
  const double area2 = ab.x() * ac.y() - ab.y() * ac.x();  // twice the projected signed area
  if (!(area2 > 0)) return;                                // seen from behind or edge-on
  const double x_lo = std::min({corners[0].x(), corners[1].x(), corners[2].x()});
  const double x_hi = std::max({corners[0].x(), corners[1].x(), corners[2].x()});
  const double y_lo = std::min({corners[0].y(), corners[1].y(), corners[2].y()});
  const double y_hi = std::max({corners[0].y(), corners[1].y(), corners[2].y()});
  // Pixel centres on the triangle's bounding box count (the inside test below has a tolerance).
  const double slack = 1e-9;
  const int col_begin = std::max(0, static_cast<int>(std::ceil((x_lo - image.x_min) / q - slack)));
  const int col_end =
      std::min(size.width - 1, static_cast<int>(std::floor((x_hi - image.x_min) / q + slack)));
  const int row_begin = std::max(0, static_cast<int>(std::ceil((image.y_max - y_hi) / q - slack)));
  const int row_end =
      std::min(size.height - 1, static_cast<int>(std::floor((image.y_max - y_lo) / q + slack)));
  const double tolerance = -1e-12 * area2;
  for (int row = row_begin; row <= row_end; ++row) {
    const double y = image.y_max - row * q;
    for (int col = col_begin; col <= col_end; ++col) {
      const double x = image.x_min + col * q;
      double weights[3];
      bool inside = true;
      for (int k = 0; k < 3; ++k) {
        const Vec3& a = corners[(k + 1) % 3];
        const Vec3& b = corners[(k + 2) % 3];
        weights[k] = ((b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x())) / area2;
        inside &= weights[k] * area2 >= tolerance;
      }
      if (!inside) continue;
      const double z =
          weights[0] * corners[0].z() + weights[1] * corners[1].z() + weights[2] * corners[2].z();
      if (!(z > depth(row, col))) continue;
      depth(row, col) = z;
      if (!mesh.has_colors()) continue;
      Rgb rgb = Rgb::Zero();
      for (int k = 0; k < 3; ++k) {
        rgb += static_cast<float>(weights[k]) * mesh.colors[mesh.triangles[face][k]];
      }
      color(row, col) = cv::Vec3f(rgb.x(), rgb.y(), rgb.z());
    }
  }
}

// Eq. 7–8: image.depth from `depth` over the known pixels of image.labels (offset and scale
// recorded), 0 elsewhere, where `color` is cleared too.
void normalise_depth(const cv::Mat_<double>& depth, const BoundaryLoop& hole, RangeImage& image,
                     cv::Mat_<cv::Vec3f>& color) {
  const cv::Size size = depth.size();
  const double q = image.step;
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  for (int row = 0; row < size.height; ++row) {
    for (int col = 0; col < size.width; ++col) {
      if (image.labels.at<std::uint8_t>(row, col) != kKnownPixel) continue;
      lowest = std::min(lowest, depth(row, col));
      highest = std::max(highest, depth(row, col));
    }
  }
  if (!(highest >= lowest)) {
    throw ProcessingError("hole " + std::to_string(hole.id) + ": no zone pixel in the range image");
  }
  image.depth_offset = lowest;
  image.depth_scale = highest - lowest > 1e-9 * q ? 1.0 / (highest - lowest) : 1.0 / q;
  image.depth = cv::Mat::zeros(size, CV_32F);
  for (int row = 0; row < size.height; ++row) {
    for (int col = 0; col < size.width; ++col) {
      if (image.labels.at<std::uint8_t>(row, col) == kKnownPixel) {
        image.depth.at<float>(row, col) =
            static_cast<float>((depth(row, col) - image.depth_offset) * image.depth_scale);
      } else {
        color(row, col) = cv::Vec3f(0, 0, 0);
      }
    }
  }
}

}  // namespace

RangeImage rasterize_zone(const Mesh& mesh, const Zone& zone, const BoundaryLoop& hole,
                          const HoleInPlane& plane, double mean_edge,
                          const RangeImageOptions& options) {
  RangeImage image;
  image.plane = plane;
  const Frame& frame = plane.frame;
  image.step = options.beta * mean_edge;  // eq. 6
  if (!(image.step > 0)) throw InvalidInput("range image: grid step must be positive");

  const std::vector<Vec2>& polygon = plane.loop;
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec2& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  for (int v : zone.vertices) {
    const Vec2 p = frame.to_local(mesh.positions[v]).head<2>();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double q = image.step;
  image.x_min = lo.x() - options.margin * q;
  image.y_max = hi.y() + options.margin * q;
  const double cols = std::ceil((hi.x() - lo.x()) / q) + 2.0 * options.margin + 1;
  const double rows = std::ceil((hi.y() - lo.y()) / q) + 2.0 * options.margin + 1;
  if (!(rows * cols <= static_cast<double>(options.max_pixels))) {
    throw ProcessingError("hole " + std::to_string(hole.id) + ": range image of " +
                          std::to_string(static_cast<long long>(cols)) + "x" +
                          std::to_string(static_cast<long long>(rows)) +
                          " pixels exceeds the limit of " + std::to_string(options.max_pixels));
  }
  const cv::Size size(static_cast<int>(cols), static_cast<int>(rows));

  // Depth buffer in double precision.
  const double empty = -std::numeric_limits<double>::infinity();
  cv::Mat_<double> depth(size, empty);
  cv::Mat_<cv::Vec3f> color(size, cv::Vec3f(0, 0, 0));
  for (int face : zone.faces) rasterize_face(mesh, face, image, depth, color);

  image.labels = cv::Mat(size, CV_8U);
  for (int row = 0; row < size.height; ++row) {
    for (int col = 0; col < size.width; ++col) {
      image.labels.at<std::uint8_t>(row, col) = depth(row, col) > empty ? kKnownPixel : kGapPixel;
    }
  }
  label_polygon_interior(polygon, image);
  label_outside(image);

  normalise_depth(depth, hole, image, color);
  if (mesh.has_colors()) image.color = color;
  return image;
}

double rim_support(const RangeImage& image, const std::vector<std::array<Vec2, 2>>& chords) {
  const cv::Mat& labels = image.labels;
  const double reach = 1.5 * image.step;
  auto near_chord = [&](int row, int col) {
    const Vec2 centre(image.x_min + col * image.step, image.y_max - row * image.step);
    return std::any_of(chords.begin(), chords.end(), [&](const std::array<Vec2, 2>& chord) {
      return distance_to_segment(centre, chord[0], chord[1]) <= reach;
    });
  };
  int border = 0, known = 0;
  for (int row = 0; row < labels.rows; ++row) {
    for (int col = 0; col < labels.cols; ++col) {
      if (labels.at<std::uint8_t>(row, col) == kHolePixel || near_chord(row, col)) continue;
      bool touches_hole = false;
      for (int dr = -1; dr <= 1 && !touches_hole; ++dr) {
        for (int dc = -1; dc <= 1 && !touches_hole; ++dc) {
          const int r = row + dr, c = col + dc;
          touches_hole = r >= 0 && r < labels.rows && c >= 0 && c < labels.cols &&
                         labels.at<std::uint8_t>(r, c) == kHolePixel;
        }
      }
      if (!touches_hole) continue;
      ++border;
      known += labels.at<std::uint8_t>(row, col) == kKnownPixel;
    }
  }
  return border == 0 ? 1.0 : static_cast<double>(known) / border;
}

namespace {

// Section VI-B on one range image: its pixels by row-major index.
class GapFiller {
 public:
  explicit GapFiller(RangeImage& image)
      : image_(image),
        rows_(image.labels.rows),
        cols_(image.labels.cols),
        area_of_(static_cast<size_t>(rows_) * cols_, -1),
        filled_neighbours_(static_cast<size_t>(rows_) * cols_, 0) {}

  // Gap areas (4-connected), each as its pixels in discovery order, smallest first.
  std::vector<std::vector<int>> gap_areas() {
    std::vector<std::vector<int>> areas;
    for (int start = 0; start < rows_ * cols_; ++start) {
      if (label(start) != kGapPixel || area_of_[start] >= 0) continue;
      std::vector<int> area{start};
      area_of_[start] = static_cast<int>(areas.size());
      for (size_t i = 0; i < area.size(); ++i) {
        for_neighbours(area[i], false, [&](int n) {
          if (label(n) == kGapPixel && area_of_[n] < 0) {
            area_of_[n] = area_of_[start];
            area.push_back(n);
          }
        });
      }
      areas.push_back(std::move(area));
    }
    std::stable_sort(areas.begin(), areas.end(),
                     [](const auto& a, const auto& b) { return a.size() < b.size(); });
    return areas;
  }

  // Fills an area from its known 8-neighbours, the pixel with most of them first (eq. 9), each the
  // mean of them (eq. 10); an area with none joins the hole.
  void fill_area(const std::vector<int>& area, GapFillStats& stats) {
    // Max-heap on (filled neighbours, then smaller row-major index): eq. 9's order.
    std::priority_queue<std::pair<int, int>> queue;
    for (int p : area) {
      int count = 0;
      for_neighbours(p, true, [&](int n) { count += label(n) == kKnownPixel; });
      filled_neighbours_[p] = count;
      if (count > 0) queue.emplace(count, -p);
    }
    if (queue.empty()) {
      for (int p : area) label(p) = kHolePixel;
      stats.joined_to_hole += static_cast<int>(area.size());
      return;
    }
    while (!queue.empty()) {
      const auto [count, negative_index] = queue.top();
      queue.pop();
      const int p = -negative_index;
      if (label(p) != kGapPixel || count != filled_neighbours_[p]) continue;  // stale entry
      double sum = 0;
      cv::Vec3d color_sum(0, 0, 0);
      for_neighbours(p, true, [&](int n) {
        if (label(n) != kKnownPixel) return;
        sum += value(n);
        if (colored()) color_sum += cv::Vec3d(color(n));
      });
      value(p) = static_cast<float>(sum / count);  // eq. 10
      if (colored()) color(p) = cv::Vec3f(color_sum / count);
      label(p) = kKnownPixel;
      ++stats.pixels;
      for_neighbours(p, true, [&](int n) {
        if (label(n) == kGapPixel && area_of_[n] == area_of_[p])
          queue.emplace(++filled_neighbours_[n], -n);
      });
    }
    ++stats.areas;
  }

  // Outside pixels take the value of the nearest known pixel.
  void extend_outside() {
    cv::Mat not_known = image_.labels != kKnownPixel;
    cv::Mat distance, nearest;
    cv::distanceTransform(not_known, distance, nearest, cv::DIST_L2, cv::DIST_MASK_5,
                          cv::DIST_LABEL_PIXEL);
    std::vector<int> known_of_label(static_cast<size_t>(rows_) * cols_ + 1, -1);
    for (int p = 0; p < rows_ * cols_; ++p) {
      if (label(p) == kKnownPixel) known_of_label[nearest.at<int>(p / cols_, p % cols_)] = p;
    }
    for (int p = 0; p < rows_ * cols_; ++p) {
      if (label(p) != kOutsidePixel) continue;
      const int source = known_of_label[nearest.at<int>(p / cols_, p % cols_)];
      value(p) = source < 0 ? 0.0f : value(source);
      if (colored()) color(p) = source < 0 ? cv::Vec3f(0, 0, 0) : color(source);
    }
  }

 private:
  std::uint8_t& label(int index) {
    return image_.labels.at<std::uint8_t>(index / cols_, index % cols_);
  }
  float& value(int index) { return image_.depth.at<float>(index / cols_, index % cols_); }
  bool colored() const { return !image_.color.empty(); }
  cv::Vec3f& color(int index) { return image_.color.at<cv::Vec3f>(index / cols_, index % cols_); }

  // visit(n) for the 4- or 8-neighbours n of pixel `index` inside the image.
  template <typename Visit>
  void for_neighbours(int index, bool eight, Visit visit) {
    const int row = index / cols_, col = index % cols_;
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        if ((dr == 0 && dc == 0) || (!eight && dr != 0 && dc != 0)) continue;
        const int r = row + dr, c = col + dc;
        if (r >= 0 && r < rows_ && c >= 0 && c < cols_) visit(r * cols_ + c);
      }
    }
  }

  RangeImage& image_;
  int rows_, cols_;
  std::vector<int> area_of_;
  std::vector<int> filled_neighbours_;
};

}  // namespace

GapFillStats fill_small_gaps(RangeImage& image) {
  GapFillStats stats;
  GapFiller filler(image);
  for (const std::vector<int>& area : filler.gap_areas()) filler.fill_area(area, stats);
  filler.extend_outside();
  return stats;
}

Trend fit_trend(const RangeImage& image, TrendKind kind, double ring) {
  return fit_trend(image.depth, image.labels, kind, ring, 1 / (image.depth_scale * image.step));
}

}  // namespace rangefill
