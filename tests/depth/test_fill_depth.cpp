// Depth maps (depth.h): fill_depth on planes, quadrics and discontinuities, its options and
// argument checks; depth image files; the renderer; sensor-like holes; sensor frames.
#include "rangefill/depth/fill_depth.h"
#include "rangefill/eval/render.h"
#include "rangefill/eval/sensor_holes.h"
#include "rangefill/io/depth_io.h"

#include <cmath>
#include <cstring>
#include <functional>
#include <map>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>

#include "rangefill/core/errors.h"
#include "rangefill/io/mesh_io.h"
#include "support.h"

namespace rangefill {
namespace {

namespace fs = std::filesystem;

const CameraIntrinsics kCamera;  // 525, 525, 319.5, 239.5
const cv::Size kSize(640, 480);

// The direction (z = 1) of the ray through pixel (col, row).
Vec3 ray(int col, int row) {
  return {(col - kCamera.cx) / kCamera.fx, (row - kCamera.cy) / kCamera.fy, 1};
}

// CV_32F metres: depth(ray) at every pixel.
cv::Mat depth_image(const std::function<double(const Vec3&)>& depth) {
  cv::Mat image(kSize, CV_32F);
  for (int row = 0; row < kSize.height; ++row) {
    for (int col = 0; col < kSize.width; ++col)
      image.at<float>(row, col) = static_cast<float>(depth(ray(col, row)));
  }
  return image;
}

// The plane n·X = d seen along a ray.
double plane_depth(const Vec3& direction, const Vec3& normal, double d) {
  return d / normal.dot(direction);
}

// The sphere |X − centre| = radius seen along a ray (its near side), 0 where missed.
double sphere_depth(const Vec3& direction, const Vec3& centre, double radius) {
  const double a = direction.squaredNorm(), b = direction.dot(centre);
  const double discriminant = b * b - a * (centre.squaredNorm() - radius * radius);
  return discriminant < 0 ? 0 : (b - std::sqrt(discriminant)) / a;
}

cv::Mat disc(cv::Point centre, int radius) {
  cv::Mat mask = cv::Mat::zeros(kSize, CV_8U);
  cv::circle(mask, centre, radius, cv::Scalar(255), cv::FILLED);
  return mask;
}

// Largest |a − b| (metres) over the mask.
double max_error(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask) {
  cv::Mat a64, b64;
  a.convertTo(a64, CV_64F);
  b.convertTo(b64, CV_64F);
  return cv::norm(a64, b64, cv::NORM_INF, mask);
}

// Every back-end restores a tilted plane, linear in inverse depth: with the plane trend exactly;
// without (the default) harmonic exactly, telea and ns within 1 % (OpenCV's weighted means).
TEST(FillDepth, RestoresATiltedPlaneWithEveryBackend) {
  const Vec3 normal = Vec3(0.3, -0.4, 1).normalized();
  const cv::Mat truth = depth_image([&](const Vec3& r) { return plane_depth(r, normal, 1.8); });
  const cv::Mat hole = disc({300, 200}, 15) | disc({500, 400}, 4);
  cv::Mat input = truth.clone();
  input.setTo(0, hole);
  for (const std::string& name : inpainter_names()) {
    for (TrendKind trend : {TrendKind::none, TrendKind::plane}) {
      DepthFillOptions options;
      options.inpainter = name;
      options.trend = trend;
      cv::Mat filled;
      const DepthFillStats stats = fill_depth(input, cv::noArray(), filled, options);
      EXPECT_EQ(stats.holes, 2) << name;
      EXPECT_EQ(stats.filled, 2) << name;
      EXPECT_EQ(stats.at_edge, 0) << name;
      EXPECT_EQ(stats.filled_pixels, cv::countNonZero(hole)) << name;
      const double tolerance = trend == TrendKind::plane || name == "harmonic" ? 1e-5 : 0.025;
      EXPECT_LT(max_error(filled, truth, hole), tolerance) << name << " " << trend_name(trend);
    }
  }
}

// A sphere (a quadric in space, not in the image): with the quadric trend every back-end restores
// a 40-pixel disc at 1.5 m within 1 mm; without (the default) within 6 mm, the fill sagging below
// the dome a little. 16-bit input comes back within a millimetre more.
TEST(FillDepth, RestoresASphereWithEveryBackend) {
  const Vec3 centre(0.1, 0, 2);
  const cv::Mat truth = depth_image([&](const Vec3& r) { return sphere_depth(r, centre, 0.5); });
  const cv::Mat hole = disc({345, 240}, 20);
  cv::Mat input = truth.clone();
  input.setTo(0, hole);
  cv::Mat truth_mm, input_mm;
  truth.convertTo(truth_mm, CV_16U, 1000);
  input.convertTo(input_mm, CV_16U, 1000);
  for (const std::string& name : inpainter_names()) {
    for (TrendKind trend : {TrendKind::none, TrendKind::quadric}) {
      DepthFillOptions options;
      options.inpainter = name;
      options.trend = trend;
      const double tolerance = trend == TrendKind::quadric ? 1e-3 : 6e-3;
      cv::Mat filled, filled_mm;
      fill_depth(input, cv::noArray(), filled, options);
      EXPECT_LT(max_error(filled, truth, hole), tolerance) << name << " " << trend_name(trend);
      fill_depth(input_mm, cv::noArray(), filled_mm, options);
      ASSERT_EQ(filled_mm.type(), CV_16UC1);
      EXPECT_LE(max_error(filled_mm, truth_mm, hole), 1000 * tolerance + 1) << name;
    }
  }
}

// A near plane (1 m, left of column 320) in front of a far one (2 m). A band on the far side of the
// edge, as a sensor shadow, and a square across the edge are both filled at the far depth (the
// background goes on behind the near plane), not bridged by a ramp.
TEST(FillDepth, DoesNotBridgeADiscontinuity) {
  cv::Mat truth(kSize, CV_32F, cv::Scalar(2.0f));
  truth.colRange(0, 320).setTo(1.0f);
  cv::Mat shadow = cv::Mat::zeros(kSize, CV_8U), square = shadow.clone();
  shadow(cv::Rect(320, 100, 12, 150)).setTo(255);
  square(cv::Rect(300, 300, 40, 40)).setTo(255);
  cv::Mat input = truth.clone();
  input.setTo(0, shadow | square);
  const cv::Mat far_depth(kSize, CV_32F, cv::Scalar(2.0f));
  for (const std::string& name : inpainter_names()) {
    DepthFillOptions options;
    options.inpainter = name;
    cv::Mat filled;
    const DepthFillStats stats = fill_depth(input, cv::noArray(), filled, options);
    EXPECT_EQ(stats.filled, 2) << name;
    EXPECT_EQ(stats.at_edge, 2) << name;
    EXPECT_LT(max_error(filled, far_depth, shadow | square), 1e-5) << name;
  }
  // Without the rule (a threshold no jump reaches) the band is a ramp.
  DepthFillOptions smooth;
  smooth.discontinuity = 10;
  cv::Mat filled;
  fill_depth(input, cv::noArray(), filled, smooth);
  EXPECT_GT(max_error(filled, truth, shadow), 0.2);
}

// A floor seen at a grazing angle (1/z linear in the row, 3 % deeper per row here) is one surface:
// a blob on it is filled from all around (no occluder), exactly.
TEST(FillDepth, ASteepSurfaceIsNoDiscontinuity) {
  cv::Mat truth(kSize, CV_32F, cv::Scalar(0));
  for (int row = 151; row < kSize.height; ++row) truth.row(row).setTo(525.0 / (row - 150));
  const cv::Mat hole = disc({320, 185}, 8);
  cv::Mat input = truth.clone();
  input.setTo(0, hole);
  cv::Mat filled;
  const DepthFillStats stats = fill_depth(input, hole, filled);
  ASSERT_GT(truth.at<float>(177, 320) / truth.at<float>(193, 320), 1.5);
  EXPECT_EQ(stats.at_edge, 0);
  cv::Mat relative;
  cv::divide(filled - truth, truth, relative);
  EXPECT_LT(cv::norm(relative, cv::NORM_INF, hole), 1e-5);
}

// Only the masked pixels change; invalid pixels outside the mask stay and are not read as depth 0;
// masked pixels are restored whatever they hold.
TEST(FillDepth, AnExplicitMaskFillsOnlyItsPixels) {
  cv::Mat input(kSize, CV_16U, cv::Scalar(1500));
  input(cv::Rect(100, 100, 30, 30)).setTo(0);    // a sensor hole, not to be filled
  input(cv::Rect(130, 100, 10, 30)).setTo(900);  // outliers to replace, beside it
  cv::Mat mask = cv::Mat::zeros(kSize, CV_8U);
  mask(cv::Rect(130, 100, 10, 30)).setTo(1);
  cv::Mat filled;
  const DepthFillStats stats = fill_depth(input, mask, filled);
  EXPECT_EQ(stats.holes, 1);
  EXPECT_EQ(stats.filled, 1);
  cv::Mat expected = input.clone();
  expected.setTo(1500, mask);
  EXPECT_EQ(cv::norm(filled, expected, cv::NORM_INF), 0);
}

// Pixels outside the holes come back bit for bit, NaN included, in the input's type; a second run
// gives the same bits; filling in place gives the same result.
TEST(FillDepth, KeepsEveryOtherPixelAndIsDeterministic) {
  cv::Mat input = depth_image([](const Vec3& r) { return sphere_depth(r, {0, 0, 2}, 1.2); });
  input.at<float>(0, 0) = std::numeric_limits<float>::quiet_NaN();  // on the border: kept
  const cv::Mat hole = disc({320, 240}, 12) | disc({200, 150}, 6);
  input.setTo(std::numeric_limits<float>::quiet_NaN(), hole);
  DepthFillOptions options;
  options.keep_border = true;
  cv::Mat first, second;
  fill_depth(input, cv::noArray(), first, options);
  fill_depth(input, cv::noArray(), second, options);
  ASSERT_EQ(first.type(), CV_32FC1);
  EXPECT_EQ(std::memcmp(first.data, second.data, first.total() * first.elemSize()), 0);
  EXPECT_TRUE(std::isnan(first.at<float>(0, 0)));
  cv::Mat outside = hole == 0;
  outside.at<std::uint8_t>(0, 0) = 0;
  EXPECT_EQ(cv::norm(first, input, cv::NORM_INF, outside), 0);
  EXPECT_EQ(cv::countNonZero(invalid_depth_mask(first) & hole), 0);
  cv::Mat in_place = input.clone();
  fill_depth(in_place, cv::noArray(), in_place, options);
  EXPECT_EQ(std::memcmp(first.data, in_place.data, first.total() * first.elemSize()), 0);
}

// Holes filled on several threads give the same image, bit for bit, and the same counts as on one:
// a ball before a wall, 16-bit, with twelve holes (some at its silhouette) and a grid of 400 bars
// two pixels apart, whose windows overlap (a write that touched a hole's neighbours would race).
TEST(FillDepth, SameResultAtAnyThreadCount) {
  cv::Mat input;
  depth_image([](const Vec3& r) {
    const double ball = sphere_depth(r, {0, 0, 2}, 0.5);
    return ball > 0 ? ball : plane_depth(r, {0, 0, 1}, 3);
  }).convertTo(input, CV_16U, 1000);
  cv::Mat hole = cv::Mat::zeros(kSize, CV_8U);
  for (int k = 0; k < 12; ++k) hole |= disc({60 + 45 * k, 120 + 20 * (k % 5)}, 3 + k % 4);
  for (int row = 300; row < 380; row += 4) {
    for (int col = 150; col < 490; col += 17) hole(cv::Rect(col, row, 15, 2)).setTo(255);
  }
  input.setTo(0, hole);
  for (const char* name : {"foe", "ns"}) {
    DepthFillOptions options;
    options.inpainter = name;
    cv::Mat one, several;
    const DepthFillStats on_one = fill_depth(input, cv::noArray(), one, options);
    EXPECT_EQ(on_one.filled, 412) << name;
    EXPECT_GT(on_one.at_edge, 0) << name;
    EXPECT_EQ(cv::countNonZero(one == 0), 0) << name;
    for (int threads : {2, 5}) {
      options.threads = threads;
      const DepthFillStats on_several = fill_depth(input, cv::noArray(), several, options);
      EXPECT_EQ(cv::norm(one, several, cv::NORM_INF), 0) << name << " " << threads;
      EXPECT_EQ(on_several.filled, on_one.filled) << name;
      EXPECT_EQ(on_several.at_edge, on_one.at_edge) << name;
      EXPECT_EQ(on_several.filled_pixels, on_one.filled_pixels) << name;
    }
  }
}

// By default every hole is filled, those on the image border too. Holes larger than
// max_hole_pixels, holes on the border with keep_border and a hole with no valid pixel around it
// are left, counted in holes and pixels by reason; filled_mask is exactly the pixels filled.
TEST(FillDepth, FillsEveryHoleUnlessAskedAndCountsWhatIsLeft) {
  cv::Mat input(kSize, CV_16U, cv::Scalar(2000));
  input(cv::Rect(0, 200, 5, 5)).setTo(0);      // on the border, 25 px
  input(cv::Rect(300, 200, 20, 20)).setTo(0);  // 400 px
  input(cv::Rect(490, 290, 25, 25)).setTo(0);  // 625 px
  input(cv::Rect(100, 100, 3, 3)).setTo(0);    // 9 px
  cv::Mat filled;
  DepthFillStats stats = fill_depth(input, cv::noArray(), filled);
  EXPECT_EQ(stats.filled, 4);
  EXPECT_EQ(stats.left_holes(), 0);
  EXPECT_EQ(stats.left_pixels(), 0);
  EXPECT_EQ(cv::countNonZero(filled != 2000), 0);
  EXPECT_EQ(cv::norm(stats.filled_mask, input == 0, cv::NORM_INF), 0);

  DepthFillOptions options;
  options.max_hole_pixels = 100;
  options.keep_border = true;
  stats = fill_depth(input, cv::noArray(), filled, options);
  EXPECT_EQ(stats.holes, 4);
  EXPECT_EQ(stats.filled, 1);
  EXPECT_EQ(stats.filled_pixels, 9);
  EXPECT_EQ(stats.at_border.holes, 1);
  EXPECT_EQ(stats.at_border.pixels, 25);
  EXPECT_EQ(stats.too_large.holes, 2);
  EXPECT_EQ(stats.too_large.pixels, 1025);
  EXPECT_EQ(stats.left_pixels(), 1050);
  cv::Mat expected = input.clone();
  expected(cv::Rect(100, 100, 3, 3)).setTo(2000);
  EXPECT_EQ(cv::norm(filled, expected, cv::NORM_INF), 0);
  EXPECT_EQ(cv::countNonZero(stats.filled_mask), 9);
  EXPECT_EQ(cv::countNonZero(stats.filled_mask(cv::Rect(100, 100, 3, 3))), 9);

  cv::Mat inner = cv::Mat::zeros(kSize, CV_8U);  // inside the invalid 25x25 square
  inner(cv::Rect(500, 300, 5, 5)).setTo(255);
  stats = fill_depth(input, inner, filled);
  EXPECT_EQ(stats.holes, 1);
  EXPECT_EQ(stats.without_support.holes, 1);
  EXPECT_EQ(stats.without_support.pixels, 25);
  EXPECT_EQ(cv::countNonZero(stats.filled_mask), 0);
  EXPECT_EQ(cv::norm(filled, input, cv::NORM_INF), 0);
}

// A hole open to the image border is extrapolated from inside with the occlusion rule: a shadow
// band beside a near box, running into the border, takes the wall's depth behind it, never the
// box's, and a band along the border continues the tilted floor's slope.
TEST(FillDepth, BorderHolesAreExtrapolatedWithTheOcclusionRule) {
  cv::Mat input(kSize, CV_16U);
  for (int row = 0; row < input.rows; ++row) {
    // A floor whose depth grows by 2 mm a row, a box at 1 m in columns 200..299.
    input.row(row).setTo(3000 + 2 * row);
  }
  input(cv::Rect(200, 0, 100, 300)).setTo(1000);  // the box, touching the top border
  cv::Mat truth = input.clone();
  input(cv::Rect(180, 0, 20, 300)).setTo(0);  // its shadow, from the top border down
  input(cv::Rect(0, 470, 640, 10)).setTo(0);  // an invalid band along the bottom border
  cv::Mat filled;
  const DepthFillStats stats = fill_depth(input, cv::noArray(), filled);
  EXPECT_EQ(stats.left_pixels(), 0);
  EXPECT_EQ(cv::countNonZero(filled == 0), 0);
  cv::Mat error;
  cv::absdiff(filled, truth, error);
  double worst = 0;
  // The border is a free edge: the slope of the floor flattens there (35 mm at the top row); the
  // box is 2 m nearer.
  cv::minMaxLoc(error(cv::Rect(180, 0, 20, 300)), nullptr, &worst);
  EXPECT_LT(worst, 50) << "the shadow took the box's depth";
  cv::minMaxLoc(error(cv::Rect(0, 470, 640, 10)), nullptr, &worst);
  EXPECT_LT(worst, 50) << "the bottom band is off the floor";
  const cv::Mat kept = input != 0;
  EXPECT_EQ(cv::norm(filled, input, cv::NORM_INF, kept), 0);
}

// Beyond `reach` pixels from every pixel it is filled from, a hole takes the nearest one's depth:
// the right half of a surface that waves along the rows, invalid up to the border, keeps each
// row's last valid depth there; with no limit the back-end's membrane flattens the wave.
TEST(FillDepth, PixelsBeyondReachTakeTheNearestDepth) {
  cv::Mat input(kSize, CV_16U);
  for (int row = 0; row < input.rows; ++row) {
    input.row(row).setTo(std::lround(1000 + 200 * std::sin(row / 30.0)));
  }
  input(cv::Rect(320, 0, 320, 480)).setTo(0);
  DepthFillOptions options;
  options.reach = 4;
  cv::Mat filled;
  fill_depth(input, cv::noArray(), filled, options);
  EXPECT_EQ(cv::norm(filled.col(639), input.col(319), cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(filled, input, cv::NORM_INF, input != 0), 0);
  options.reach = 0;
  fill_depth(input, cv::noArray(), filled, options);
  EXPECT_EQ(cv::countNonZero(filled == 0), 0);
  EXPECT_EQ(cv::norm(filled, input, cv::NORM_INF, input != 0), 0);
  double lowest = 0, highest = 0;
  cv::minMaxLoc(filled.col(639), &lowest, &highest);
  EXPECT_LT(highest - lowest, 40);  // the wave spans 400 mm at column 319
}

// Wrong types and a mask of another size are refused with a one-line message saying what is wrong.
TEST(FillDepth, RefusesBadArguments) {
  const cv::Mat depth(48, 64, CV_16U, cv::Scalar(1000));
  cv::Mat out;
  try {
    fill_depth(depth, cv::Mat::zeros(48, 60, CV_8U), out);
    FAIL() << "no exception";
  } catch (const InvalidInput& error) {
    EXPECT_STREQ(error.what(), "fill_depth: mask is 60x48 but depth is 64x48");
  }
  EXPECT_THROW(fill_depth(cv::Mat(48, 64, CV_8U), cv::noArray(), out), InvalidInput);
  EXPECT_THROW(fill_depth(cv::Mat(48, 64, CV_32FC3), cv::noArray(), out), InvalidInput);
  EXPECT_THROW(fill_depth(depth, cv::Mat::zeros(48, 64, CV_16U), out), InvalidInput);
  DepthFillOptions options;
  options.inpainter = "no-such-back-end";
  EXPECT_THROW(fill_depth(depth, cv::noArray(), out, options), InvalidInput);
  for (const auto& spoil : std::vector<std::function<void(DepthFillOptions&)>>{
           [](DepthFillOptions& o) { o.discontinuity = 0; },
           [](DepthFillOptions& o) { o.margin = 0; },
           [](DepthFillOptions& o) { o.max_hole_pixels = -1; },
           [](DepthFillOptions& o) { o.threads = 0; }}) {
    DepthFillOptions bad;
    spoil(bad);
    EXPECT_THROW(fill_depth(depth, cv::noArray(), out, bad), InvalidInput);
  }
}

// ---------------------------------------------------------------------------------------------
// Files

cv::Mat sample_depth(int type) {
  cv::Mat depth(37, 53, type);
  cv::randu(depth, 0, type == CV_16UC1 ? 65535 : 9.5);
  depth(cv::Rect(3, 4, 5, 6)).setTo(0);
  if (type == CV_32FC1) depth.at<float>(10, 10) = std::numeric_limits<float>::quiet_NaN();
  return depth;
}

bool bit_identical(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() &&
         std::memcmp(a.data, b.data, a.total() * a.elemSize()) == 0;
}

// 16-bit PNG and TIFF, float TIFF and EXR come back bit for bit (NaN included); the write is atomic
// (no temporary file left).
TEST(DepthFiles, RoundTripsBitForBit) {
  const fs::path dir = testing::temporary_directory("depth-files");
  for (const char* name : {"a.png", "a.tif", "b.TIFF"}) {
    const cv::Mat depth = sample_depth(CV_16UC1);
    write_depth_image(depth, dir / name);
    EXPECT_TRUE(bit_identical(read_depth_image(dir / name), depth)) << name;
  }
  for (const char* name : {"c.tiff", "c.exr"}) {
    const cv::Mat depth = sample_depth(CV_32FC1);
    write_depth_image(depth, dir / name);
    EXPECT_TRUE(bit_identical(read_depth_image(dir / name), depth)) << name;
  }
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 5);
  fs::remove_all(dir);
}

std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return "no exception";
}

// Unreadable files and images that are not depth give one-line errors naming the file; formats
// that cannot hold the type are refused before writing.
TEST(DepthFiles, ClearErrorsForBadFiles) {
  const fs::path dir = testing::temporary_directory("depth-bad");
  const std::string missing = (dir / "missing.png").string();
  EXPECT_THROW(read_depth_image(missing), IoError);
  EXPECT_EQ(message_of([&] { read_depth_image(missing); }).rfind(missing + ": cannot open", 0), 0u);

  write_file_atomically("not an image at all", dir / "text.png");
  EXPECT_EQ(message_of([&] { read_depth_image(dir / "text.png"); }),
            (dir / "text.png").string() + ": not a PNG, TIFF or EXR image");
  const std::string png16 = [&] {
    write_depth_image(sample_depth(CV_16UC1), dir / "full.png");
    return read_file(dir / "full.png");
  }();
  write_file_atomically(png16.substr(0, png16.size() / 2), dir / "truncated.png");
  EXPECT_THROW(read_depth_image(dir / "truncated.png"), InvalidInput);

  cv::imwrite((dir / "gray8.png").string(), cv::Mat(4, 4, CV_8U, cv::Scalar(7)));
  EXPECT_EQ(message_of([&] { read_depth_image(dir / "gray8.png"); }),
            (dir / "gray8.png").string() +
                ": CV_8UC1 is not depth: expected 16-bit unsigned (millimetres) or 32-bit float "
                "(metres)");
  cv::imwrite((dir / "rgb.png").string(), cv::Mat(4, 4, CV_16UC3, cv::Scalar(7, 8, 9)));
  EXPECT_EQ(message_of([&] { read_depth_image(dir / "rgb.png"); }),
            (dir / "rgb.png").string() + ": has 3 channels; a depth or mask image has one");
  EXPECT_EQ(cv::countNonZero(read_mask_image(dir / "gray8.png")), 16);

  EXPECT_EQ(message_of([&] { write_depth_image(sample_depth(CV_32FC1), dir / "f.png"); }),
            (dir / "f.png").string() +
                ": PNG holds 16-bit depth only; write float depth to .tif or .exr");
  EXPECT_THROW(write_depth_image(sample_depth(CV_16UC1), dir / "f.exr"), InvalidInput);
  EXPECT_THROW(write_depth_image(sample_depth(CV_16UC1), dir / "f.jpg"), InvalidInput);
  EXPECT_THROW(write_depth_image(sample_depth(CV_16UC1), dir / "no-such-dir" / "f.png"), IoError);
  fs::remove_all(dir);
}

// A damaged PNG is refused by the PNG check (src/png_check.h) before OpenCV sees it: one line
// naming the file, and nothing printed by libpng (which, under OpenCV, reports to stderr).
TEST(DepthFiles, DamagedPngsAreRefusedWithoutLibpngOutput) {
  const fs::path dir = testing::temporary_directory("depth-png");
  const cv::Mat depth = sample_depth(CV_16UC1);
  write_depth_image(depth, dir / "full.png");
  const std::string png = read_file(dir / "full.png");
  std::string crc = png;
  crc[png.size() - 20] ^= 0x40;  // a byte of the last IDAT chunk (IEND takes the last 12)
  std::string type = png;
  type[12] = '1';  // IHDR's type
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"truncated.png", png.substr(0, png.size() / 2)},
      {"crc.png", crc},
      {"type.png", type},
      {"no-iend.png", png.substr(0, png.size() - 12)},
      {"header-only.png", png.substr(0, 33) + png.substr(png.size() - 12)},
  };
  for (const auto& [name, bytes] : cases) {
    SCOPED_TRACE(name);
    const fs::path path = dir / name;  // a lambda may not capture a structured binding in C++17
    write_file_atomically(bytes, path);
    ::testing::internal::CaptureStderr();
    const std::string message = message_of([&] { read_depth_image(path); });
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    EXPECT_EQ(message.rfind(path.string() + ": corrupt PNG: ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
  EXPECT_TRUE(bit_identical(read_depth_image(dir / "full.png"), depth));
  fs::remove_all(dir);

  // The PNG fuzzer's corpus (tests/fuzz/corpus/png, with its findings): each file is read or
  // refused with one line naming it, silently.
  const fs::path corpus = fs::path(RANGEFILL_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / "png";
  int read = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(corpus)) {
    SCOPED_TRACE(entry.path().filename().string());
    ::testing::internal::CaptureStderr();
    const std::string message = message_of([&] { read_depth_image(entry.path()); });
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    read += message == "no exception";
    if (message != "no exception") {
      EXPECT_EQ(message.rfind(entry.path().string() + ": ", 0), 0u) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos);
    }
  }
  EXPECT_EQ(read, 2);  // the 16-bit greyscale ones, interlaced or not
}

// ---------------------------------------------------------------------------------------------
// Rendering

// A quad of the plane z = 2 (camera looking along +z from the origin) renders as that plane; a
// tilted one as the analytic depth of its plane; outside it nothing.
TEST(RenderDepth, RendersPlanesExactly) {
  const Mesh quad =
      make_mesh({{-1, -1, 2}, {1, -1, 2}, {1, 1, 2}, {-1, 1, 2}}, {{0, 1, 2}, {0, 2, 3}});
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  const cv::Mat flat = render_depth(quad, kCamera, identity, kSize);
  // The quad spans ±1 m at 2 m: columns 319.5 ± 262.5, rows 239.5 ± 262.5 (all of them).
  EXPECT_EQ(cv::countNonZero(flat), (582 - 57 + 1) * 480);
  EXPECT_EQ(flat.at<float>(240, 320), 2.0f);
  EXPECT_EQ(flat.at<float>(240, 40), 0.0f);

  // Seen from (0.5, 0.3, −1) looking at (0, 0, 2): the plane z = 2 in camera coordinates.
  const Eigen::Isometry3d pose = look_at({0.5, 0.3, -1}, {0, 0, 2}, {0, -1, 0});
  const Vec3 normal_world(0, 0, 1);
  const Vec3 normal = pose.linear() * normal_world;
  const double d = normal.dot(pose * Vec3(0, 0, 2));
  const cv::Mat tilted = render_depth(quad, kCamera, pose, kSize);
  const cv::Mat truth = depth_image([&](const Vec3& r) { return plane_depth(r, normal, d); });
  EXPECT_GT(cv::countNonZero(tilted), 50000);
  EXPECT_LT(max_error(tilted, truth, tilted != 0), 1e-5);
}

// look_at puts the target on the optical axis, `up` up in the image, and keeps distances.
TEST(RenderDepth, LookAtPointsTheCamera) {
  const Eigen::Isometry3d pose = look_at({1, 2, 3}, {4, 6, 3}, {0, 0, 1});
  const Vec3 target = pose * Vec3(4, 6, 3);
  EXPECT_NEAR(target.x(), 0, 1e-12);
  EXPECT_NEAR(target.y(), 0, 1e-12);
  EXPECT_NEAR(target.z(), 5, 1e-12);
  EXPECT_LT((pose * Vec3(4, 6, 4) - target).y(), 0);  // up is −y
  EXPECT_NEAR(pose.linear().determinant(), 1, 1e-12);
  EXPECT_THROW(look_at({0, 0, 0}, {0, 0, 1}, {0, 0, 1}), InvalidInput);
}

// A closed sphere renders without cracks (every pixel inside its silhouette has depth) and close to
// the analytic sphere; the nearest surface wins over a plane behind it.
TEST(RenderDepth, RendersAClosedMeshWithoutCracks) {
  Mesh sphere = testing::make_sphere(24);
  for (Vec3& p : sphere.positions) p = p * 0.5 + Vec3(0, 0, 2);
  const Mesh wall =
      make_mesh({{-9, -9, 4}, {9, -9, 4}, {9, 9, 4}, {-9, 9, 4}}, {{0, 1, 2}, {0, 2, 3}});
  Mesh scene = sphere;
  for (const Triangle& t : wall.triangles) {
    scene.triangles.push_back(
        {t[0] + sphere.vertex_count(), t[1] + sphere.vertex_count(), t[2] + sphere.vertex_count()});
  }
  scene.positions.insert(scene.positions.end(), wall.positions.begin(), wall.positions.end());
  const cv::Mat depth = render_depth(scene, kCamera, Eigen::Isometry3d::Identity(), kSize);
  EXPECT_EQ(cv::countNonZero(depth), kSize.area());
  const cv::Mat truth = depth_image([](const Vec3& r) { return sphere_depth(r, {0, 0, 2}, 0.5); });
  // The inscribed polyhedron's silhouette lies within the sphere's; on the cap facing the camera
  // (up to 53° from the axis) depth is within a few times the chord error (0.16 mm).
  EXPECT_EQ(cv::countNonZero((depth < 3) & (truth == 0)), 0);
  EXPECT_LT(max_error(depth, truth, (truth > 0) & (truth < 1.7)), 1e-3);
}

// ---------------------------------------------------------------------------------------------
// Sensor-like holes

// Punched pixels are valid ones, about `fraction` of them, the same for a seed, other for another;
// with a depth edge, shadows lie on its far side.
TEST(PunchDepthHoles, PunchesValidPixelsDeterministically) {
  cv::Mat depth(kSize, CV_16U, cv::Scalar(3000));
  depth.colRange(300, 640).setTo(1500);
  depth(cv::Rect(0, 0, 640, 20)).setTo(0);
  SensorHoleOptions options;
  options.fraction = 0.05;
  const cv::Mat punched = punch_depth_holes(depth, options);
  const double valid = cv::countNonZero(depth);
  EXPECT_EQ(cv::countNonZero(punched & (depth == 0)), 0);
  EXPECT_NEAR(cv::countNonZero(punched) / valid, 0.05, 0.005);
  EXPECT_EQ(cv::norm(punched, punch_depth_holes(depth, options), cv::NORM_INF), 0);
  options.seed = 2;
  EXPECT_GT(cv::norm(punched, punch_depth_holes(depth, options), cv::NORM_L1), 0);
  // Shadows: left of the near surface, on the far pixels next to the edge.
  EXPECT_GT(cv::countNonZero(punched.col(299)), 20);
  EXPECT_GT(cv::countNonZero(punched.col(299)), 2 * cv::countNonZero(punched.col(300)));
}

// ---------------------------------------------------------------------------------------------
// Sensor frames (../shared/data/depth-real)

// On the sensor frames with 5 % sensor-like holes, every back-end fills every punched pixel and
// beats plain cv::inpaint (the better of Telea and Navier–Stokes on the 16-bit frame, every invalid
// pixel masked) in RMSE over the punched pixels of the four frames.
TEST(FillDepth, BeatsCvInpaintOnSensorFrames) {
  RANGEFILL_REQUIRE_SHARED(shared);
  std::map<std::string, double> squared;
  long long pixels = 0;
  for (const char* name : {"tum.png", "sun3d.png", "open3d-depth.png", "livingroom-00000.png"}) {
    const cv::Mat truth = read_depth_image(shared / "depth-real" / name);
    ASSERT_EQ(truth.type(), CV_16UC1) << name;
    const cv::Mat punched = punch_depth_holes(truth);
    cv::Mat input = truth.clone();
    input.setTo(0, punched);
    pixels += cv::countNonZero(punched);
    const auto add = [&](const std::string& method, const cv::Mat& filled) {
      cv::Mat error;
      cv::absdiff(filled, truth, error);
      error.convertTo(error, CV_64F);
      squared[method] += cv::norm(error, cv::NORM_L2SQR, punched);
    };
    for (const std::string& backend : inpainter_names()) {
      DepthFillOptions options;
      options.inpainter = backend;
      cv::Mat filled;
      fill_depth(input, punched, filled, options);
      EXPECT_EQ(cv::countNonZero(punched & (filled == 0)), 0) << name << " " << backend;
      add(backend, filled);
    }
    for (const int flags : {cv::INPAINT_TELEA, cv::INPAINT_NS}) {
      cv::Mat filled;
      cv::inpaint(input, input == 0, filled, 5, flags);
      add("cv::inpaint " + std::to_string(flags), filled);
    }
  }
  const double baseline = std::sqrt(std::min(squared["cv::inpaint 0"], squared["cv::inpaint 1"]) /
                                    static_cast<double>(pixels));
  for (const std::string& backend : inpainter_names()) {
    EXPECT_LT(std::sqrt(squared[backend] / static_cast<double>(pixels)), baseline) << backend;
  }
}

}  // namespace
}  // namespace rangefill
