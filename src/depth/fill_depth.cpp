#include "rangefill/depth/fill_depth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "depth/color_guide.h"
#include "depth/fill_along_lines.h"
#include "rangefill/core/errors.h"
#include "rangefill/core/parallel.h"
#include "rangefill/inpaint/harmonic.h"
#include "rangefill/inpaint/inpainters.h"
#include "rangefill/inpaint/pixel_labels.h"

namespace rangefill {

namespace {

std::string size_text(cv::Size size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

// The plane of the scene through a valid pixel: inverse depth, and its gradient (per pixel) fitted
// to the valid pixels within 2 pixels on the same surface (0 when they do not determine it).
struct LocalPlane {
  double inverse = 0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  cv::Point origin;
  double at(cv::Point p) const {
    return inverse + gradient.dot(Eigen::Vector2d(p.x - origin.x, p.y - origin.y));
  }
};

LocalPlane local_plane(const cv::Mat& z, const cv::Mat& data, cv::Point p, double discontinuity) {
  LocalPlane plane;
  plane.inverse = 1 / z.at<float>(p);
  plane.origin = p;
  std::vector<Eigen::Vector3d> rows;
  std::vector<double> values;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      const cv::Point q = p + cv::Point(dx, dy);
      if (q.x < 0 || q.y < 0 || q.x >= z.cols || q.y >= z.rows || !data.at<std::uint8_t>(q) ||
          !same_surface(z.at<float>(q), z.at<float>(p), discontinuity)) {
        continue;
      }
      rows.emplace_back(1, dx, dy);
      values.push_back(1 / z.at<float>(q));
    }
  }
  if (rows.size() < 3) return plane;
  Eigen::MatrixXd a(rows.size(), 3);
  Eigen::VectorXd b(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    a.row(i) = rows[i].transpose();
    b[i] = values[i];
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() == 3) plane.gradient = qr.solve(b).tail<2>();
  return plane;
}

// Step 1 of fill_depth: which rim pixels occlude. From rim pixel p, across the hole in each of the
// 8 directions, the first valid pixel q lies behind p when deeper by more than `discontinuity` and
// p is nearer than q's local plane continued to p by as much.
std::vector<bool> occluding(const cv::Mat& z, const cv::Mat& data, const cv::Mat& hole,
                            const std::vector<cv::Point>& rim, double discontinuity) {
  const cv::Rect window(0, 0, z.cols, z.rows);
  std::vector<bool> front(rim.size(), false);
  for (size_t i = 0; i < rim.size(); ++i) {
    for (int dy = -1; dy <= 1 && !front[i]; ++dy) {
      for (int dx = -1; dx <= 1 && !front[i]; ++dx) {
        const cv::Point step(dx, dy);
        cv::Point q = rim[i] + step;
        if (!window.contains(q) || !hole.at<std::uint8_t>(q)) continue;  // (0, 0) included
        while (window.contains(q) && hole.at<std::uint8_t>(q)) q += step;
        if (!window.contains(q) || !data.at<std::uint8_t>(q)) continue;
        const float near = z.at<float>(rim[i]);
        front[i] =
            z.at<float>(q) > (1 + discontinuity) * near &&
            1 / near > (1 + discontinuity) * local_plane(z, data, q, discontinuity).at(rim[i]);
      }
    }
  }
  return front;
}

// Distances (pixels) within `hole` from the pixels of `seeds` along 8-neighbour paths through
// the hole (a chamfer transform in two raster sweeps each way), CV_32F; infinite where no path
// reaches. cv::distanceTransform measures straight across what is not hole.
cv::Mat distance_through(const cv::Mat& hole, const cv::Mat& seeds) {
  cv::Mat distance(hole.size(), CV_32F, cv::Scalar(std::numeric_limits<float>::infinity()));
  distance.setTo(0, seeds);
  const std::array<cv::Point, 4> before = {{{-1, -1}, {0, -1}, {1, -1}, {-1, 0}}};
  const auto relax = [&](int row, int col, int direction) {
    float& best = distance.at<float>(row, col);
    for (const cv::Point& step : before) {
      const cv::Point q = cv::Point(col, row) + direction * step;
      if (q.x < 0 || q.y < 0 || q.x >= hole.cols || q.y >= hole.rows) continue;
      const float length = step.x != 0 && step.y != 0 ? std::sqrt(2.0F) : 1.0F;
      best = std::min(best, distance.at<float>(q) + length);
    }
  };
  for (int sweep = 0; sweep < 2; ++sweep) {
    for (int row = 0; row < hole.rows; ++row) {
      for (int col = 0; col < hole.cols; ++col) {
        if (hole.at<std::uint8_t>(row, col)) relax(row, col, 1);
      }
    }
    for (int row = hole.rows - 1; row >= 0; --row) {
      for (int col = hole.cols - 1; col >= 0; --col) {
        if (hole.at<std::uint8_t>(row, col)) relax(row, col, -1);
      }
    }
  }
  return distance;
}

// The hole pixels that see occluding rim pixels first along more than half of the 8 directions
// (through the hole) that meet the rim: inside an occluder's silhouette continued across the
// hole. A sensor's shadow beside an occluder sees it on one side only. `rim`: CV_8U, 1 at rim
// pixels that occlude, 2 at the others, 0 elsewhere.
cv::Mat inside_silhouette(const cv::Mat& hole, const cv::Mat& rim) {
  cv::Mat occluders(hole.size(), CV_8U, cv::Scalar(0)), seen = occluders.clone();
  cv::Mat first(hole.size(), CV_8U);  // the kind of the first rim pixel along one direction
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      // Rows and columns in the order that visits p + (dx, dy) before p.
      for (int i = 0; i < hole.rows; ++i) {
        const int row = dy > 0 ? hole.rows - 1 - i : i;
        for (int j = 0; j < hole.cols; ++j) {
          const int col = dx > 0 ? hole.cols - 1 - j : j;
          if (!hole.at<std::uint8_t>(row, col)) continue;
          const cv::Point next(col + dx, row + dy);
          std::uint8_t kind = 0;
          if (next.x >= 0 && next.y >= 0 && next.x < hole.cols && next.y < hole.rows) {
            kind = hole.at<std::uint8_t>(next) ? first.at<std::uint8_t>(next)
                                               : rim.at<std::uint8_t>(next);
          }
          first.at<std::uint8_t>(row, col) = kind;
          occluders.at<std::uint8_t>(row, col) += kind == 1;
          seen.at<std::uint8_t>(row, col) += kind != 0;
        }
      }
    }
  }
  return hole & (2 * occluders > seen);
}

// How much nearer (pixels) the occluding rim pixels than the others a hole pixel must be to lie on
// the near side: the background goes on behind an occluder, a sensor's shadow beside it is on the
// far side; and how near an occluding rim pixel a hole pixel must be for the sides to decide its
// surface (step 4). Chosen on the depth kit's tuning frames (docs/depth-maps.md).
constexpr float kNearSideMargin = 6;

// Steps 1–2 of fill_depth for a hole's window: the hole's pixels on the far and the near side of
// the occluding edges its rim sees, and the valid pixels each side is filled from.
struct HoleSides {
  cv::Mat back, front;                // CV_8U, the hole's pixels on either side
  cv::Mat back_source, front_source;  // CV_8U; empty when the side has no pixel
  cv::Mat beside_edge;   // CV_8U, hole pixels within kNearSideMargin of an occluding rim pixel
  bool at_edge = false;  // some rim pixels occlude
  bool supported() const { return !back_source.empty() || !front_source.empty(); }
};

// The sides of `hole` (step 2 of fill_depth): each valid pixel of the window belongs to the side
// of its nearest rim pixel, occluding or not, when on that pixel's surface; a hole pixel is on the
// near side when it is nearer the occluding rim pixels than the others, through the hole, by more
// than kNearSideMargin. A side without valid pixels gives its hole pixels to the other.
HoleSides hole_sides(const cv::Mat& z, const cv::Mat& data, const cv::Mat& hole,
                     double discontinuity) {
  HoleSides sides;
  cv::Mat rim_mask;
  cv::dilate(hole, rim_mask, cv::Mat::ones(3, 3, CV_8U));
  rim_mask &= data;
  std::vector<cv::Point> rim;
  cv::findNonZero(rim_mask, rim);
  if (rim.empty()) return sides;
  const std::vector<bool> front = occluding(z, data, hole, rim, discontinuity);
  sides.at_edge = std::find(front.begin(), front.end(), true) != front.end();
  if (!sides.at_edge) {
    sides.back = hole;
    sides.back_source = data;
    return sides;
  }
  cv::Mat distance, nearest;
  cv::distanceTransform(rim_mask == 0, distance, nearest, cv::DIST_L2, cv::DIST_MASK_5,
                        cv::DIST_LABEL_PIXEL);
  std::vector<int> rim_of_label(rim.size() + 1, -1);
  for (size_t i = 0; i < rim.size(); ++i)
    rim_of_label[nearest.at<int>(rim[i])] = static_cast<int>(i);
  cv::Mat back_source = cv::Mat::zeros(z.size(), CV_8U), front_source = back_source.clone();
  for (int row = 0; row < z.rows; ++row) {
    for (int col = 0; col < z.cols; ++col) {
      if (!data.at<std::uint8_t>(row, col)) continue;
      const int r = rim_of_label[nearest.at<int>(row, col)];
      if (same_surface(z.at<float>(row, col), z.at<float>(rim[r]), discontinuity)) {
        (front[r] ? front_source : back_source).at<std::uint8_t>(row, col) = 255;
      }
    }
  }
  // Distances through the hole to the occluding rim pixels and to the others.
  cv::Mat front_rim = cv::Mat::zeros(z.size(), CV_8U), back_rim = front_rim.clone();
  for (size_t i = 0; i < rim.size(); ++i) {
    (front[i] ? front_rim : back_rim).at<std::uint8_t>(rim[i]) = 255;
  }
  const cv::Mat to_front = distance_through(hole, front_rim);
  const cv::Mat to_back = distance_through(hole, back_rim);
  sides.beside_edge = hole & (to_front <= kNearSideMargin);
  sides.front = (to_front + kNearSideMargin < to_back) &
                inside_silhouette(hole, front_rim / 255 + back_rim / 128);
  if (cv::countNonZero(back_source) == 0) sides.front = hole;
  if (cv::countNonZero(front_source) == 0) sides.front.setTo(0);
  sides.back = hole & ~sides.front;
  if (cv::countNonZero(sides.back) > 0) sides.back_source = back_source;
  if (cv::countNonZero(sides.front) > 0) sides.front_source = front_source;
  return sides;
}

// Before step 3 of fill_depth: every pixel of the window farther than `reach` from the source
// takes the depth of its nearest source pixel and joins the source, so that the back-end restores
// a band of `reach` pixels along the source however large the hole is. `z` is replaced by a copy
// when it changes.
void extend_source_beyond_reach(cv::Mat& z, cv::Mat& source, int reach) {
  cv::Mat distance, nearest;
  cv::distanceTransform(source == 0, distance, nearest, cv::DIST_L2, cv::DIST_MASK_5,
                        cv::DIST_LABEL_PIXEL);
  const cv::Mat far = distance > reach;
  if (cv::countNonZero(far) == 0) return;
  std::vector<cv::Point> source_pixels;
  cv::findNonZero(source, source_pixels);
  std::vector<float> depth_of_label(source_pixels.size() + 1, 0);
  for (const cv::Point& p : source_pixels) depth_of_label[nearest.at<int>(p)] = z.at<float>(p);
  z = z.clone();
  for (int row = 0; row < z.rows; ++row) {
    for (int col = 0; col < z.cols; ++col) {
      if (far.at<std::uint8_t>(row, col))
        z.at<float>(row, col) = depth_of_label[nearest.at<int>(row, col)];
    }
  }
  source |= far;
}

// Step 3 of fill_depth: depth (metres) at the hole pixels of a window, restored from `source`;
// the back-end guided by the window's `color` (CV_32FC3) when there is one and it reads a guide.
cv::Mat fill_from_source(const cv::Mat& z, const cv::Mat& hole, const cv::Mat& source,
                         const cv::Mat& color, const Inpainter& backend,
                         const DepthFillOptions& options) {
  const std::unique_ptr<Inpainter> guided =
      color.empty() ? nullptr : backend.guided(color, kColorSigma);
  const Inpainter& inpainter = guided ? *guided : backend;
  // The source in inverse depth, normalised onto [0, 1].
  cv::Mat inverse;
  cv::divide(1.0, z, inverse, CV_32F);
  double lowest = 0, highest = 0;
  cv::minMaxLoc(inverse, &lowest, &highest, nullptr, nullptr, source);
  const double scale = highest > lowest ? 1 / (highest - lowest) : 1;
  cv::Mat labels(z.size(), CV_8U, cv::Scalar(kGapPixel));
  labels.setTo(kHolePixel, hole);
  labels.setTo(kKnownPixel, source);
  cv::Mat normalised = (inverse - lowest) * scale, values = cv::Mat::zeros(z.size(), CV_32F);
  normalised.copyTo(values, source);

  // Perspective pixels are no length unit (height unit 0): a sphere (or auto) trend is fitted as
  // a quadric.
  TrendKind fitted = TrendKind::none;
  const cv::Mat restored = inpaint_residual(values, labels, labels != kKnownPixel, inpainter,
                                            options.trend, options.trend_ring, 0, fitted);
  cv::Mat filled(z.size(), CV_32F, cv::Scalar(0));
  for (int row = 0; row < z.rows; ++row) {
    for (int col = 0; col < z.cols; ++col) {
      if (!hole.at<std::uint8_t>(row, col)) continue;
      const double value = std::clamp<double>(restored.at<float>(row, col), -0.5, 1.5);
      filled.at<float>(row, col) =
          static_cast<float>(1 / std::max(lowest + value / scale, lowest / 2));
    }
  }
  return filled;
}

// Step 4 of fill_depth: the hole pixels that lie between two valid pixels of one surface along a
// line (fill_along_lines over every valid pixel of the window interpolates them) and not beside
// an occluding edge take the lines' depth where `fill` (step 3) put them on another surface: away
// from an edge, the sides' rule has no reason to move a pixel off the surface around it.
void keep_interpolated_surfaces(const cv::Mat& z, const cv::Mat& data, const cv::Mat& hole,
                                const cv::Mat& beside_edge, const cv::Mat& color,
                                double discontinuity, cv::Mat& fill) {
  cv::Mat interpolated;
  const cv::Mat lines = fill_along_lines(z, data, hole, discontinuity, 1, color, &interpolated);
  for (int row = 0; row < fill.rows; ++row) {
    for (int col = 0; col < fill.cols; ++col) {
      float& value = fill.at<float>(row, col);
      const float line_value = lines.at<float>(row, col);
      if (interpolated.at<std::uint8_t>(row, col) &&
          (beside_edge.empty() || !beside_edge.at<std::uint8_t>(row, col)) &&
          !same_surface(value, line_value, discontinuity)) {
        value = line_value;
      }
    }
  }
}

struct HoleOutcome {
  enum Kind { filled, too_large, at_border, without_support } kind = filled;
  int pixels = 0;
  bool at_edge = false;
};

// The bounding box of hole `label` (connectedComponentsWithStats' `stats`).
cv::Rect hole_box(const cv::Mat& stats, int label) {
  return {stats.at<int>(label, cv::CC_STAT_LEFT), stats.at<int>(label, cv::CC_STAT_TOP),
          stats.at<int>(label, cv::CC_STAT_WIDTH), stats.at<int>(label, cv::CC_STAT_HEIGHT)};
}

// Whether hole `label` is to be filled (kind filled) or left for a reason the options give
// (too large, at the border when kept), before anything is read of it.
HoleOutcome hole_outcome_by_size(const cv::Mat& stats, int label, cv::Size image,
                                 const DepthFillOptions& options) {
  const cv::Rect box = hole_box(stats, label);
  HoleOutcome outcome;
  outcome.pixels = stats.at<int>(label, cv::CC_STAT_AREA);
  const bool touches_border = box.x == 0 || box.y == 0 || box.x + box.width == image.width ||
                              box.y + box.height == image.height;
  if (options.max_hole_pixels > 0 && outcome.pixels > options.max_hole_pixels) {
    outcome.kind = HoleOutcome::too_large;
  } else if (touches_border && options.keep_border) {
    outcome.kind = HoleOutcome::at_border;
  }
  return outcome;
}

// Writes a fill of `metres` at pixel `p` of `out` (of the depth's type). Pixel by pixel:
// cv::Mat::copyTo with a mask may store whole vectors, neighbours included, which would race with
// the holes filled at once around this one.
void write_fill(cv::Mat& out, cv::Point p, float metres) {
  if (out.type() == CV_16UC1) {  // millimetres, rounded; a fill is never 0 (invalid)
    out.at<std::uint16_t>(p) =
        std::max<std::uint16_t>(cv::saturate_cast<std::uint16_t>(1000.0 * metres), 1);
  } else {
    out.at<float>(p) = metres;
  }
}

// Fills hole `label` of `labels` (connectedComponentsWithStats' labels and `stats`) into `out`,
// the output image (of the depth's type), at the hole's pixels only: each side of the hole
// (hole_sides) from its own source, by the back-end if the hole is small enough for it
// (options.backend_max_pixels), else along lines (always with a null back-end).
HoleOutcome fill_depth_hole(const cv::Mat& z, const cv::Mat& data, const cv::Mat& color,
                            const cv::Mat& labels, const cv::Mat& stats, int label,
                            const Inpainter* inpainter, const DepthFillOptions& options,
                            cv::Mat& out) {
  HoleOutcome outcome = hole_outcome_by_size(stats, label, z.size(), options);
  if (outcome.kind != HoleOutcome::filled) return outcome;
  const cv::Rect box = hole_box(stats, label);
  const int m = options.margin;
  const cv::Rect window = cv::Rect(box.x - m, box.y - m, box.width + 2 * m, box.height + 2 * m) &
                          cv::Rect(0, 0, z.cols, z.rows);
  const cv::Mat hole = labels(window) == label;
  const cv::Mat window_color = color.empty() ? cv::Mat() : color(window);
  const HoleSides sides = hole_sides(z(window), data(window), hole, options.discontinuity);
  if (!sides.supported()) {
    outcome.kind = HoleOutcome::without_support;
    return outcome;
  }
  outcome.at_edge = sides.at_edge;
  const Inpainter* backend =
      options.backend_max_pixels == 0 || outcome.pixels <= options.backend_max_pixels ? inpainter
                                                                                      : nullptr;
  cv::Mat fill(window.size(), CV_32F, cv::Scalar(0));
  for (const auto& [side, side_source] :
       {std::pair{sides.back, sides.back_source}, {sides.front, sides.front_source}}) {
    if (side_source.empty()) continue;
    cv::Mat side_fill;
    if (backend == nullptr) {
      side_fill =
          fill_along_lines(z(window), side_source, side, options.discontinuity, 1, window_color);
    } else {
      cv::Mat window_z = z(window), source = side_source.clone();
      if (options.reach > 0) extend_source_beyond_reach(window_z, source, options.reach);
      side_fill = fill_from_source(window_z, side, source, window_color, *backend, options);
    }
    side_fill.copyTo(fill, side);
  }
  // A side whose lines see none of its source (a near side cut off from its occluder) is filled
  // from every valid pixel of the window.
  const cv::Mat unfilled = hole & (fill == 0);
  if (cv::countNonZero(unfilled) > 0) {
    fill_along_lines(z(window), data(window), unfilled, options.discontinuity, 1, window_color)
        .copyTo(fill, unfilled);
  }
  // Without an edge or a back-end, step 3 was this same fill along lines.
  if (sides.at_edge || backend != nullptr) {
    keep_interpolated_surfaces(z(window), data(window), hole, sides.beside_edge, window_color,
                               options.discontinuity, fill);
  }
  for (int row = 0; row < window.height; ++row) {
    for (int col = 0; col < window.width; ++col) {
      if (hole.at<std::uint8_t>(row, col)) {
        write_fill(out, cv::Point(window.x + col, window.y + row), fill.at<float>(row, col));
      }
    }
  }
  return outcome;
}

// The pixels of the holes whose label maps to non-zero in `chosen` (CV_8UC1, 255 there), given
// the labels and the mask of all holes (label > 0), which is returned itself when all are chosen.
cv::Mat holes_mask(const cv::Mat& labels, const std::vector<std::uint8_t>& chosen,
                   const cv::Mat& all_holes) {
  if (std::all_of(chosen.begin() + 1, chosen.end(), [](std::uint8_t c) { return c != 0; })) {
    return all_holes;
  }
  cv::Mat mask(labels.size(), CV_8U);
  for (int row = 0; row < labels.rows; ++row) {
    const int* label = labels.ptr<int>(row);
    std::uint8_t* value = mask.ptr<std::uint8_t>(row);
    for (int col = 0; col < labels.cols; ++col) value[col] = chosen[label[col]] ? 255 : 0;
  }
  return mask;
}

// fill_depth with options.fast: the holes to fill (`all_holes`, but those left for their size)
// at once by fill_along_lines.
std::vector<HoleOutcome> fill_depth_along_lines(const cv::Mat& z, const cv::Mat& data,
                                                const cv::Mat& color, const cv::Mat& labels,
                                                const cv::Mat& stats, const cv::Mat& all_holes,
                                                const DepthFillOptions& options, cv::Mat& out) {
  std::vector<HoleOutcome> outcomes(std::max(0, stats.rows - 1));
  std::vector<std::uint8_t> to_fill_label(stats.rows, 0);
  for (size_t i = 0; i < outcomes.size(); ++i) {
    outcomes[i] = hole_outcome_by_size(stats, static_cast<int>(i) + 1, z.size(), options);
    if (outcomes[i].kind == HoleOutcome::filled) to_fill_label[i + 1] = 255;
  }
  const cv::Mat to_fill = holes_mask(labels, to_fill_label, all_holes);
  const cv::Mat fill =
      fill_along_lines(z, data, to_fill, options.discontinuity, options.threads, color);
  // A hole is filled whole or not at all (fill_along_lines fills a pixel's 8 neighbours in the
  // round after it): one without a fill had no data on any line through it.
  for (int row = 0; row < z.rows; ++row) {
    const std::uint8_t* chosen = to_fill.ptr<std::uint8_t>(row);
    const float* metres = fill.ptr<float>(row);
    for (int col = 0; col < z.cols; ++col) {
      if (!chosen[col]) continue;
      if (metres[col] > 0) {
        write_fill(out, cv::Point(col, row), metres[col]);
      } else {
        outcomes[labels.at<int>(row, col) - 1].kind = HoleOutcome::without_support;
      }
    }
  }
  return outcomes;
}

}  // namespace

std::vector<std::string> depth_filler_names() {
  std::vector<std::string> names = {kAlongLines};
  for (const std::string& name : inpainter_names()) names.push_back(name);
  return names;
}

InpainterOptions depth_inpainting_defaults() {
  InpainterOptions options;
  options.foe.start = "telea";
  options.foe.tolerance = 3e-3;
  options.foe.iterations = 10;
  return options;
}

DepthFillStats fill_depth(cv::InputArray depth, cv::InputArray invalid_mask, cv::OutputArray filled,
                          const DepthFillOptions& options) {
  check_depth_type(depth.type(), "fill_depth");
  if (depth.empty()) throw InvalidInput("fill_depth: the depth image is empty");
  const cv::Mat source = depth.getMat();
  const cv::Mat z = depth_in_metres(source);
  cv::Mat to_fill, data;
  if (invalid_mask.empty()) {
    to_fill = z == 0;
    data = to_fill == 0;
  } else {
    if (invalid_mask.type() != CV_8UC1) {
      throw InvalidInput("fill_depth: mask must be CV_8UC1, not " +
                         cv::typeToString(invalid_mask.type()));
    }
    if (invalid_mask.size() != source.size()) {
      throw InvalidInput("fill_depth: mask is " + size_text(invalid_mask.size()) +
                         " but depth is " + size_text(source.size()));
    }
    to_fill = invalid_mask.getMat() != 0;
    data = (z > 0) & (to_fill == 0);
  }
  if (!(options.discontinuity > 0) || options.margin < 1 || options.max_hole_pixels < 0 ||
      options.backend_max_pixels < 0 || options.threads < 1) {
    throw InvalidInput(
        "fill_depth: discontinuity must be positive, margin and threads at least 1 and "
        "max_hole_pixels and backend_max_pixels not negative");
  }
  const cv::Mat color = guide_color(options.color, source.size(), "fill_depth");
  const std::unique_ptr<Inpainter> inpainter =
      options.fast || options.inpainter == kAlongLines
          ? nullptr
          : make_inpainter(options.inpainter, options.inpainting);

  cv::Mat labels, stats, centroids;
  const int components =
      cv::connectedComponentsWithStats(to_fill, labels, stats, centroids, 8, CV_32S, cv::CCL_BBDT);
  source.copyTo(filled);
  cv::Mat out = filled.getMat();
  std::vector<HoleOutcome> outcomes(std::max(0, components - 1));
  std::vector<std::exception_ptr> failures(outcomes.size());
  if (options.fast) {
    outcomes = fill_depth_along_lines(z, data, color, labels, stats, to_fill, options, out);
  } else {
    // Holes are independent: each reads the input only and writes its own pixels, so they can
    // run at once; outcomes (and a failure, the first in hole order) are taken in hole order.
    parallel_for(static_cast<int>(outcomes.size()), options.threads, [&](int i) {
      try {
        outcomes[i] =
            fill_depth_hole(z, data, color, labels, stats, i + 1, inpainter.get(), options, out);
      } catch (...) {
        failures[i] = std::current_exception();
      }
    });
  }
  DepthFillStats result;
  result.holes = static_cast<int>(outcomes.size());
  std::vector<std::uint8_t> filled_label(components, 0);
  for (size_t i = 0; i < outcomes.size(); ++i) {
    if (failures[i]) std::rethrow_exception(failures[i]);
    const HoleOutcome& outcome = outcomes[i];
    DepthFillStats::Left* left = nullptr;
    switch (outcome.kind) {
      case HoleOutcome::filled:
        ++result.filled;
        result.filled_pixels += outcome.pixels;
        result.at_edge += outcome.at_edge;
        filled_label[i + 1] = 255;
        break;
      case HoleOutcome::too_large:
        left = &result.too_large;
        break;
      case HoleOutcome::at_border:
        left = &result.at_border;
        break;
      case HoleOutcome::without_support:
        left = &result.without_support;
        break;
    }
    if (left) {
      ++left->holes;
      left->pixels += outcome.pixels;
    }
  }
  result.filled_mask = holes_mask(labels, filled_label, to_fill);
  return result;
}

}  // namespace rangefill
