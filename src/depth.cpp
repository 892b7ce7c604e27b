#include "rangefill/depth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <queue>
#include <random>

#include <Eigen/Dense>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "png_check.h"
#include "rangefill/errors.h"
#include "rangefill/io.h"
#include "rangefill/parallel.h"
#include "rangefill/range_image.h"

namespace rangefill {

namespace {

namespace fs = std::filesystem;

void check_depth_type(int type, const std::string& who) {
  if (type != CV_16UC1 && type != CV_32FC1) {
    throw InvalidInput(who + ": depth must be CV_16UC1 (millimetres) or CV_32FC1 (metres), not " +
                       cv::typeToString(type));
  }
}

std::string size_text(cv::Size size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

// Depth in metres, CV_32F, 0 where invalid.
cv::Mat metres(const cv::Mat& depth) {
  cv::Mat z;
  depth.convertTo(z, CV_32F, depth.type() == CV_16UC1 ? 1e-3 : 1.0);
  z.forEach<float>([](float& value, const int*) {
    if (!(value > 0 && value < std::numeric_limits<float>::infinity())) value = 0;
  });
  return z;
}

bool same_surface(float a, float b, double discontinuity) {
  return std::max(a, b) <= (1 + discontinuity) * std::min(a, b);
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

// Step 2 of fill_depth: the valid pixels of a window the hole is filled from, CV_8U: those whose
// nearest rim pixel does not occlude and is on the same surface. Empty when the hole has no rim.
// `at_edge` tells whether some rim pixels occlude.
cv::Mat fill_source(const cv::Mat& z, const cv::Mat& data, const cv::Mat& hole,
                    double discontinuity, bool& at_edge) {
  cv::Mat rim_mask;
  cv::dilate(hole, rim_mask, cv::Mat::ones(3, 3, CV_8U));
  rim_mask &= data;
  std::vector<cv::Point> rim;
  cv::findNonZero(rim_mask, rim);
  if (rim.empty()) return {};
  const std::vector<bool> front = occluding(z, data, hole, rim, discontinuity);
  at_edge = std::find(front.begin(), front.end(), true) != front.end();
  if (!at_edge) return data;

  cv::Mat distance, nearest;
  cv::distanceTransform(rim_mask == 0, distance, nearest, cv::DIST_L2, cv::DIST_MASK_5,
                        cv::DIST_LABEL_PIXEL);
  std::vector<int> rim_of_label(rim.size() + 1, -1);
  for (size_t i = 0; i < rim.size(); ++i)
    rim_of_label[nearest.at<int>(rim[i])] = static_cast<int>(i);
  cv::Mat source = cv::Mat::zeros(z.size(), CV_8U);
  for (int row = 0; row < z.rows; ++row) {
    for (int col = 0; col < z.cols; ++col) {
      if (!data.at<std::uint8_t>(row, col)) continue;
      const int r = rim_of_label[nearest.at<int>(row, col)];
      if (!front[r] && same_surface(z.at<float>(row, col), z.at<float>(rim[r]), discontinuity)) {
        source.at<std::uint8_t>(row, col) = 255;
      }
    }
  }
  return source;
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

// Step 3 of fill_depth: depth (metres) at the hole pixels of a window, restored from `source`.
cv::Mat fill_from_source(const cv::Mat& z, const cv::Mat& hole, const cv::Mat& source,
                         const Inpainter& inpainter, const DepthFillOptions& options) {
  // The source in inverse depth, normalised onto [0, 1].
  cv::Mat inverse;
  cv::divide(1.0, z, inverse, CV_32F);
  double lowest = 0, highest = 0;
  cv::minMaxLoc(inverse, &lowest, &highest, nullptr, nullptr, source);
  const double scale = highest > lowest ? 1 / (highest - lowest) : 1;
  RangeImage image;  // only depth and labels, what fit_trend reads
  image.labels = cv::Mat(z.size(), CV_8U, cv::Scalar(kGapPixel));
  image.labels.setTo(kHolePixel, hole);
  image.labels.setTo(kKnownPixel, source);
  image.depth = cv::Mat::zeros(z.size(), CV_32F);
  cv::Mat normalised = (inverse - lowest) * scale;
  normalised.copyTo(image.depth, source);

  // Perspective pixels are no length unit: a sphere (or auto) trend is fitted as a quadric.
  const Trend trend = fit_trend(image.depth, image.labels, options.trend, options.trend_ring);
  const cv::Mat trend_image =
      trend.kind == TrendKind::none ? cv::Mat::zeros(z.size(), CV_32F) : trend.image(z.size());
  cv::Mat restored;
  inpainter.inpaint(image.depth - trend_image, image.labels != kKnownPixel, restored);
  restored += trend_image;
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

struct HoleOutcome {
  enum Kind { filled, too_large, at_border, without_support } kind = filled;
  int pixels = 0;
  bool at_edge = false;
};

// Fills hole `label` of `labels` (connectedComponentsWithStats' labels and `stats`) into `out`,
// the output image (of the depth's type), at the hole's pixels only.
HoleOutcome fill_hole(const cv::Mat& z, const cv::Mat& data, const cv::Mat& labels,
                      const cv::Mat& stats, int label, const Inpainter& inpainter,
                      const DepthFillOptions& options, cv::Mat& out) {
  const cv::Rect box(stats.at<int>(label, cv::CC_STAT_LEFT), stats.at<int>(label, cv::CC_STAT_TOP),
                     stats.at<int>(label, cv::CC_STAT_WIDTH),
                     stats.at<int>(label, cv::CC_STAT_HEIGHT));
  HoleOutcome outcome;
  outcome.pixels = stats.at<int>(label, cv::CC_STAT_AREA);
  if (options.max_hole_pixels > 0 && outcome.pixels > options.max_hole_pixels) {
    outcome.kind = HoleOutcome::too_large;
    return outcome;
  }
  const bool touches_border =
      box.x == 0 || box.y == 0 || box.x + box.width == z.cols || box.y + box.height == z.rows;
  if (touches_border && options.keep_border) {
    outcome.kind = HoleOutcome::at_border;
    return outcome;
  }
  const int m = options.margin;
  const cv::Rect window = cv::Rect(box.x - m, box.y - m, box.width + 2 * m, box.height + 2 * m) &
                          cv::Rect(0, 0, z.cols, z.rows);
  const cv::Mat hole = labels(window) == label;
  cv::Mat source =
      fill_source(z(window), data(window), hole, options.discontinuity, outcome.at_edge);
  if (source.empty()) {
    outcome.kind = HoleOutcome::without_support;
    return outcome;
  }
  cv::Mat window_z = z(window);
  if (options.reach > 0) extend_source_beyond_reach(window_z, source, options.reach);
  const cv::Mat fill = fill_from_source(window_z, hole, source, inpainter, options);
  // Pixel by pixel: cv::Mat::copyTo with a mask may store whole vectors, neighbours included,
  // which would race with the holes around this one.
  for (int row = 0; row < window.height; ++row) {
    for (int col = 0; col < window.width; ++col) {
      if (!hole.at<std::uint8_t>(row, col)) continue;
      const float metres = fill.at<float>(row, col);
      const cv::Point p(window.x + col, window.y + row);
      if (out.type() == CV_16UC1) {  // millimetres, rounded; a fill is never 0 (invalid)
        out.at<std::uint16_t>(p) =
            std::max<std::uint16_t>(cv::saturate_cast<std::uint16_t>(1000.0 * metres), 1);
      } else {
        out.at<float>(p) = metres;
      }
    }
  }
  return outcome;
}

}  // namespace

InpainterOptions depth_inpainting_defaults() {
  InpainterOptions options;
  options.foe_start = "telea";
  options.foe_tolerance = 3e-3;
  options.foe_iterations = 10;
  return options;
}

cv::Mat invalid_depth_mask(cv::InputArray depth) {
  check_depth_type(depth.type(), "invalid_depth_mask");
  return metres(depth.getMat()) == 0;
}

DepthFillStats fill_depth(cv::InputArray depth_in, cv::InputArray mask_in, cv::OutputArray filled,
                          const DepthFillOptions& options) {
  check_depth_type(depth_in.type(), "fill_depth");
  const cv::Mat depth = depth_in.getMat();
  cv::Mat to_fill;
  if (mask_in.empty()) {
    to_fill = invalid_depth_mask(depth);
  } else {
    if (mask_in.type() != CV_8UC1) {
      throw InvalidInput("fill_depth: mask must be CV_8UC1, not " +
                         cv::typeToString(mask_in.type()));
    }
    if (mask_in.size() != depth.size()) {
      throw InvalidInput("fill_depth: mask is " + size_text(mask_in.size()) + " but depth is " +
                         size_text(depth.size()));
    }
    to_fill = mask_in.getMat() != 0;
  }
  if (!(options.discontinuity > 0) || options.margin < 1 || options.max_hole_pixels < 0 ||
      options.threads < 1) {
    throw InvalidInput(
        "fill_depth: discontinuity must be positive, margin and threads at least 1 and "
        "max_hole_pixels not negative");
  }
  const std::unique_ptr<Inpainter> inpainter =
      make_inpainter(options.inpainter, options.inpainting);
  const cv::Mat z = metres(depth);
  const cv::Mat data = (z > 0) & (to_fill == 0);

  cv::Mat labels, stats, centroids;
  const int components = cv::connectedComponentsWithStats(to_fill, labels, stats, centroids, 8);
  depth.copyTo(filled);
  cv::Mat out = filled.getMat();
  // Holes are independent: each reads the input only and writes its own pixels, so they can run
  // at once; outcomes (and a failure, the first in hole order) are taken in hole order.
  std::vector<HoleOutcome> outcomes(std::max(0, components - 1));
  std::vector<std::exception_ptr> failures(outcomes.size());
  parallel_for(static_cast<int>(outcomes.size()), options.threads, [&](int i) {
    try {
      outcomes[i] = fill_hole(z, data, labels, stats, i + 1, *inpainter, options, out);
    } catch (...) {
      failures[i] = std::current_exception();
    }
  });
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
  result.filled_mask = cv::Mat::zeros(depth.size(), CV_8U);
  result.filled_mask.forEach<std::uint8_t>([&](std::uint8_t& value, const int* position) {
    value = filled_label[labels.at<int>(position[0], position[1])];
  });
  return result;
}

// ---------------------------------------------------------------------------------------------
// Files

namespace {

std::string lower_extension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// The image in a file, as stored (cv::IMREAD_UNCHANGED), with one channel.
cv::Mat decode_single_channel(const fs::path& path) {
  const std::string bytes = read_file(path);
  if (bytes.empty()) throw InvalidInput(path.string() + ": file is empty");
  if (detail::is_png(bytes)) detail::check_png(bytes, path.string());
  cv::Mat image;
  try {
    image = cv::imdecode(
        cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, const_cast<char*>(bytes.data())),
        cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {  // its text is OpenCV's assertion, not a word for the user
    image.release();
  }
  if (image.empty()) {
    throw InvalidInput(path.string() + ": not a PNG, TIFF or EXR image" +
                       (lower_extension(path) == ".exr"
                            ? " (or OpenCV's OpenEXR codec is off: OPENCV_IO_ENABLE_OPENEXR=1 "
                              "turns it on)"
                            : ""));
  }
  if (image.channels() != 1) {
    throw InvalidInput(path.string() + ": has " + std::to_string(image.channels()) +
                       " channels; a depth or mask image has one");
  }
  return image;
}

}  // namespace

cv::Mat read_depth_image(const fs::path& path) {
  cv::Mat image = decode_single_channel(path);
  if (image.type() != CV_16UC1 && image.type() != CV_32FC1) {
    throw InvalidInput(path.string() + ": " + cv::typeToString(image.type()) +
                       " is not depth: expected 16-bit unsigned (millimetres) or 32-bit float "
                       "(metres)");
  }
  return image;
}

cv::Mat read_mask_image(const fs::path& path) {
  return decode_single_channel(path) != 0;
}

bool is_depth_image_path(const fs::path& path) {
  const std::string extension = lower_extension(path);
  return extension == ".png" || extension == ".tif" || extension == ".tiff" || extension == ".exr";
}

void check_depth_format(const fs::path& path, int type) {
  check_depth_type(type, path.string());
  if (!is_depth_image_path(path)) {
    throw InvalidInput(path.string() + ": unknown depth image format '" +
                       path.extension().string() + "' (expected .png, .tif, .tiff or .exr)");
  }
  const std::string extension = lower_extension(path);
  if (extension == ".png" && type != CV_16UC1) {
    throw InvalidInput(path.string() +
                       ": PNG holds 16-bit depth only; write float depth to .tif or .exr");
  }
  if (extension == ".exr" && type != CV_32FC1) {
    throw InvalidInput(path.string() +
                       ": EXR holds float depth only; write 16-bit depth to .png or .tif");
  }
}

namespace {

// Encodes `image` in the format of `path`'s extension and writes it atomically.
void encode_and_write(const cv::Mat& image, const fs::path& path) {
  std::vector<std::uint8_t> bytes;
  bool encoded = false;
  try {
    encoded = cv::imencode(lower_extension(path), image, bytes);
  } catch (const cv::Exception&) {
  }
  if (!encoded) {
    throw IoError(path.string() + ": OpenCV could not encode a " + cv::typeToString(image.type()) +
                  " image as " + lower_extension(path));
  }
  write_file_atomically(std::string(bytes.begin(), bytes.end()), path);
}

}  // namespace

void write_depth_image(const cv::Mat& depth, const fs::path& path) {
  check_depth_format(path, depth.type());
  encode_and_write(depth, path);
}

void write_mask_image(const cv::Mat& mask, const fs::path& path) {
  const std::string extension = lower_extension(path);
  if (mask.type() != CV_8UC1) {
    throw InvalidInput(path.string() + ": a mask is CV_8UC1, not " + cv::typeToString(mask.type()));
  }
  if (extension != ".png" && extension != ".tif" && extension != ".tiff") {
    throw InvalidInput(path.string() + ": a mask is written as .png, .tif or .tiff");
  }
  encode_and_write(mask, path);
}

// ---------------------------------------------------------------------------------------------
// Rendering

Eigen::Isometry3d look_at(const Vec3& eye, const Vec3& target, const Vec3& up) {
  const Vec3 forward = (target - eye).normalized();
  const Vec3 right = forward.cross(up);
  if (!((target - eye).norm() > 0) || !(right.norm() > 1e-12 * up.norm())) {
    throw InvalidInput("look_at: the view direction is undefined or parallel to up");
  }
  Eigen::Matrix3d rotation;  // rows: the camera's x (right), y (down), z (forward) in the world
  rotation.row(0) = right.normalized();
  rotation.row(2) = forward;
  rotation.row(1) = forward.cross(rotation.row(0).transpose());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  pose.translation() = -rotation * eye;
  return pose;
}

namespace {

// Z-buffers a triangle given by camera-space corners in front of the camera (z > 0): pixel centres
// inside it (either orientation, edges included), 1/z interpolated linearly in the image.
void rasterize(const std::array<Vec3, 3>& corners, const CameraIntrinsics& camera,
               cv::Mat_<float>& depth) {
  std::array<Vec3, 3> image;  // (u, v, 1/z)
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = corners[k];
    image[k] = {camera.fx * p.x() / p.z() + camera.cx, camera.fy * p.y() / p.z() + camera.cy,
                1 / p.z()};
  }
  const Vec3 &a = image[0], &b = image[1], &c = image[2];
  const double area2 = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  if (area2 == 0) return;  // seen edge-on
  // The pixel range of the bounding box, clamped before any conversion (corners near the camera
  // project far outside the image).
  const auto first = [](double lowest, int size) {
    return static_cast<int>(std::clamp(std::ceil(lowest), 0.0, static_cast<double>(size)));
  };
  const auto last = [](double highest, int size) {
    return static_cast<int>(std::clamp(std::floor(highest), -1.0, size - 1.0));
  };
  const int col_begin = first(std::min({a.x(), b.x(), c.x()}), depth.cols);
  const int col_end = last(std::max({a.x(), b.x(), c.x()}), depth.cols);
  const int row_begin = first(std::min({a.y(), b.y(), c.y()}), depth.rows);
  const int row_end = last(std::max({a.y(), b.y(), c.y()}), depth.rows);
  for (int row = row_begin; row <= row_end; ++row) {
    for (int col = col_begin; col <= col_end; ++col) {
      double inverse_z = 0;
      bool inside = true;
      for (int k = 0; k < 3 && inside; ++k) {
        const Vec3& p = image[(k + 1) % 3];
        const Vec3& q = image[(k + 2) % 3];
        const double weight =
            ((q.x() - p.x()) * (row - p.y()) - (q.y() - p.y()) * (col - p.x())) / area2;
        inside = weight >= -1e-9;
        inverse_z += weight * image[k].z();
      }
      if (!inside) continue;
      const float z = static_cast<float>(1 / inverse_z);
      float& pixel = depth(row, col);
      if (pixel == 0 || z < pixel) pixel = z;
    }
  }
}

}  // namespace

cv::Mat render_depth(const Mesh& mesh, const CameraIntrinsics& camera,
                     const Eigen::Isometry3d& world_to_camera, cv::Size size, double near) {
  std::vector<Vec3> local(mesh.positions.size());
  for (size_t i = 0; i < local.size(); ++i) local[i] = world_to_camera * mesh.positions[i];
  cv::Mat_<float> depth(size, 0.0f);
  for (const Triangle& triangle : mesh.triangles) {
    // The part at z >= near (Sutherland–Hodgman against one plane), fanned into triangles.
    std::vector<Vec3> kept;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = local[triangle[k]];
      const Vec3& q = local[triangle[(k + 1) % 3]];
      if (p.z() >= near) kept.push_back(p);
      if ((p.z() >= near) != (q.z() >= near))
        kept.push_back(p + (q - p) * ((near - p.z()) / (q.z() - p.z())));
    }
    for (size_t k = 2; k < kept.size(); ++k)
      rasterize({kept[0], kept[k - 1], kept[k]}, camera, depth);
  }
  return std::move(depth);
}

// ---------------------------------------------------------------------------------------------
// Sensor-like holes

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
  const cv::Mat z = metres(depth_in.getMat());
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
