// fill_depth on planes, quadrics and discontinuities, its options and argument checks, and on
// sensor frames.
#include "rangefill/core/render.h"
#include "rangefill/depth/fill_depth.h"
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

#include "depth_scenes.h"
#include "rangefill/core/errors.h"
#include "rangefill/io/mesh_io.h"
#include "support.h"

namespace rangefill {
namespace {

using namespace testing::depth_scenes;

// Every back-end restores a tilted plane, linear in inverse depth: with the plane trend exactly;
// without (the default) harmonic exactly, telea and ns within 1 % (OpenCV's weighted means).
TEST(FillDepth, RestoresATiltedPlaneWithEveryBackend) {
  const Vec3 normal = Vec3(0.3, -0.4, 1).normalized();
  const cv::Mat truth = depth_image([&](const Vec3& r) { return plane_depth(r, normal, 1.8); });
  const cv::Mat hole = disc({300, 200}, 15) | disc({500, 400}, 4);
  cv::Mat input = truth.clone();
  input.setTo(0, hole);
  for (const std::string& name : depth_filler_names()) {
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
  for (const std::string& name : depth_filler_names()) {
    for (TrendKind trend : {TrendKind::none, TrendKind::quadric}) {
      DepthFillOptions options;
      options.inpainter = name;
      options.trend = trend;
      // Lines read no trend.
      const double tolerance = trend == TrendKind::quadric && name != kAlongLines ? 1e-3 : 6e-3;
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
// edge, as a sensor shadow, is filled at the far depth (the background goes on behind the near
// plane), not bridged by a ramp; a square across the edge takes each plane on its side, the near
// one ending within kNearSideMargin and a little of the silhouette.
TEST(FillDepth, DoesNotBridgeADiscontinuity) {
  cv::Mat truth(kSize, CV_32F, cv::Scalar(2.0f));
  truth.colRange(0, 320).setTo(1.0f);
  cv::Mat shadow = cv::Mat::zeros(kSize, CV_8U), square = shadow.clone();
  shadow(cv::Rect(320, 100, 12, 150)).setTo(255);
  square(cv::Rect(300, 300, 40, 40)).setTo(255);
  cv::Mat input = truth.clone();
  input.setTo(0, shadow | square);
  const cv::Mat far_depth(kSize, CV_32F, cv::Scalar(2.0f));
  for (const std::string& name : depth_filler_names()) {
    DepthFillOptions options;
    options.inpainter = name;
    cv::Mat filled;
    const DepthFillStats stats = fill_depth(input, cv::noArray(), filled, options);
    EXPECT_EQ(stats.filled, 2) << name;
    EXPECT_EQ(stats.at_edge, 2) << name;
    cv::Mat far_of_square = square.clone(), near_of_square = square.clone();
    far_of_square.colRange(0, 320).setTo(0);
    near_of_square.colRange(308, 640).setTo(0);
    EXPECT_LT(max_error(filled, far_depth, shadow | far_of_square), 1e-5) << name;
    EXPECT_LT(max_error(filled, truth, near_of_square), 1e-5) << name;
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
  cv::Mat input = ball_before_wall_mm();
  cv::Mat hole = twelve_discs();
  for (int row = 300; row < 380; row += 4) {
    for (int col = 150; col < 490; col += 17) hole(cv::Rect(col, row, 15, 2)).setTo(255);
  }
  input.setTo(0, hole);
  for (const char* name : {kAlongLines, "foe", "ns"}) {
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
  // The border is a free edge: the slope of the floor flattens there, which the bound allows; the
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
  options.inpainter = "harmonic";  // the back-ends read reach
  options.backend_max_pixels = 0;  // this hole is larger than the default's
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

// A hole across a near object's straight silhouette: the object goes on across it, and the wall
// behind fills the rest; the near side ends short of the silhouette continued, by at most
// kNearSideMargin and a little (the far side is preferred, as for a sensor's shadow).
TEST(FillDepth, ANearSurfaceGoesOnAcrossTheSilhouetteAHoleCrosses) {
  cv::Mat truth(kSize, CV_32F, cv::Scalar(2.0f));
  truth.colRange(0, 320).setTo(1.0f);
  const cv::Mat hole = disc({320, 240}, 30);
  cv::Mat input = truth.clone();
  input.setTo(0, hole);
  cv::Mat filled;
  const DepthFillStats stats = fill_depth(input, cv::noArray(), filled);
  EXPECT_EQ(stats.at_edge, 1);
  cv::Mat far_from_silhouette = hole.clone();
  far_from_silhouette.colRange(305, 321).setTo(0);
  EXPECT_LT(max_error(filled, truth, far_from_silhouette), 1e-5);
}

// A slit into a near surface from a hole across its silhouette: the slit's rim does not occlude,
// so the sides' rule puts the slit on the far side, filled from the near surface and the wall
// behind at once; every slit pixel between two pixels of the near surface, away from the occluding
// edge, is on the near surface (step 4).
TEST(FillDepth, APixelBetweenTwoPixelsOfOneSurfaceAwayFromAnEdgeIsOnIt) {
  cv::Mat truth(kSize, CV_32F, cv::Scalar(3.0f));
  truth.rowRange(240, 480).setTo(1.0f);
  cv::Mat hole = disc({320, 240}, 30);
  hole(cv::Rect(318, 240, 5, 240)).setTo(255);
  cv::Mat input = truth.clone();
  input.setTo(0, hole);
  cv::Mat filled;
  const DepthFillStats stats = fill_depth(input, cv::noArray(), filled);
  EXPECT_EQ(stats.at_edge, 1);
  cv::Mat away_from_edge = hole.clone();
  away_from_edge.rowRange(0, 248).setTo(0);
  EXPECT_LT(max_error(filled, truth, away_from_edge), 1e-3);
}

// A colour image parts what depth alone cannot: a picture 3 % in front of its wall (one surface
// under the 5 % discontinuity) keeps its depth up to its colour edge, where without colour the
// fill blends the two across the hole; along lines, by the (default) harmonic back-end and by foe.
class ColourGuidance : public ::testing::TestWithParam<std::string> {};

TEST_P(ColourGuidance, AColourEdgePartsTheGuessesOfOneSurface) {
  cv::Mat truth(kSize, CV_32F, cv::Scalar(2.0f));
  cv::Mat color(kSize, CV_8UC3, cv::Scalar(200, 200, 200));
  truth(cv::Rect(200, 150, 120, 180)).setTo(1.94f);
  color(cv::Rect(200, 150, 120, 180)).setTo(cv::Scalar(40, 60, 160));
  const cv::Mat hole = disc({320, 240}, 20);
  cv::Mat input = truth.clone();
  input.setTo(0, hole);
  cv::Mat plain, guided;
  DepthFillOptions options;
  options.inpainter = GetParam();
  fill_depth(input, cv::noArray(), plain, options);
  options.color = color;
  fill_depth(input, cv::noArray(), guided, options);
  const double without = cv::norm(plain, truth, cv::NORM_L2, hole);
  const double with = cv::norm(guided, truth, cv::NORM_L2, hole);
  EXPECT_GT(without, 0.05);
  EXPECT_LT(with, 0.5 * without);
  EXPECT_EQ(cv::norm(guided, input, cv::NORM_INF, hole == 0), 0);
  // Grey guides as the same colours in three channels do.
  cv::Mat grey, from_grey;
  cv::cvtColor(color, grey, cv::COLOR_BGR2GRAY);
  cv::Mat grey_three;
  cv::cvtColor(grey, grey_three, cv::COLOR_GRAY2BGR);
  options.color = grey;
  fill_depth(input, cv::noArray(), from_grey, options);
  options.color = grey_three;
  fill_depth(input, cv::noArray(), guided, options);
  EXPECT_EQ(cv::norm(from_grey, guided, cv::NORM_INF), 0);
}

INSTANTIATE_TEST_SUITE_P(FillDepth, ColourGuidance,
                         ::testing::Values(kAlongLines, "harmonic", "foe"));

// A colour image of another size or type is refused, saying which.
TEST(FillDepth, RefusesAColourImageThatDoesNotMatch) {
  const cv::Mat depth(48, 64, CV_16U, cv::Scalar(1000));
  cv::Mat out;
  for (const auto& [color, message] :
       {std::pair{cv::Mat(48, 60, CV_8UC3, cv::Scalar(0)),
                  "fill_depth: the colour image is 60x48 but the depth is 64x48"},
        {cv::Mat(48, 64, CV_16UC3, cv::Scalar(0)),
         "fill_depth: the colour image must be 8-bit colour or grey, not CV_16UC3"}}) {
    DepthFillOptions options;
    options.color = color;
    try {
      fill_depth(depth, cv::noArray(), out, options);
      ADD_FAILURE() << "no exception: " << message;
    } catch (const InvalidInput& error) {
      EXPECT_STREQ(error.what(), message);
    }
  }
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
  EXPECT_THROW(fill_depth(cv::Mat(0, 0, CV_16UC1), cv::noArray(), out), InvalidInput);
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
    for (const std::string& backend : depth_filler_names()) {
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
  for (const std::string& backend : depth_filler_names()) {
    EXPECT_LT(std::sqrt(squared[backend] / static_cast<double>(pixels)), baseline) << backend;
  }
}

}  // namespace
}  // namespace rangefill
