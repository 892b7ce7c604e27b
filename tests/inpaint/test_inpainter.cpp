// Inpainting back-ends (inpainter.h, opencv_inpaint.h): the registry, the argument
// checks, known pixels kept bit for bit, and regression tests for the two OpenCV 4.6 bugs the
// wrapper works around (each test also shows the raw cv::inpaint bug, so that it fails when the
// workaround goes or when OpenCV fixes the bug and the workaround can go).
#include "rangefill/inpaint/inpainters.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>

#include "rangefill/core/errors.h"
#include "rangefill/inpaint/harmonic.h"

namespace rangefill {
namespace {

// Largest |out − expected| over the non-zero pixels of `mask`.
double max_error_in(const cv::Mat& out, double expected, const cv::Mat& mask) {
  cv::Mat as_double;
  out.convertTo(as_double, CV_64F);
  double lowest = 0, highest = 0;
  cv::minMaxLoc(as_double, &lowest, &highest, nullptr, nullptr, mask);
  return std::max(std::abs(lowest - expected), std::abs(highest - expected));
}

// The registry knows "telea" and "ns", in that order, and makes back-ends of those names.
TEST(MakeInpainter, MakesTheNamedBackends) {
  const std::vector<std::string> names = inpainter_names();
  for (const char* expected : {"telea", "ns", "harmonic"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  }
  for (const std::string& name : inpainter_names()) EXPECT_EQ(make_inpainter(name)->name(), name);
}

// An unknown name throws InvalidInput naming it and listing the known ones.
TEST(MakeInpainter, UnknownNameThrowsListingTheKnownOnes) {
  try {
    make_inpainter("no-such-back-end");
    FAIL() << "no exception";
  } catch (const InvalidInput& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'no-such-back-end'"), std::string::npos) << message;
    EXPECT_NE(message.find("telea, ns"), std::string::npos) << message;
  }
  EXPECT_THROW(make_inpainter("Telea"), InvalidInput);  // names are exact
  EXPECT_THROW(make_inpainter(""), InvalidInput);
}

// Depth must be CV_32FC1, the mask CV_8UC1 of the same size; otherwise InvalidInput naming the
// caller, from the checker and from every back-end.
TEST(CheckInpaintArguments, RefusesWrongTypesAndSizes) {
  const cv::Mat depth(4, 5, CV_32F, cv::Scalar(0)), mask(4, 5, CV_8U, cv::Scalar(0));
  EXPECT_NO_THROW(check_inpaint_arguments(depth, mask, "test"));
  EXPECT_THROW(check_inpaint_arguments(cv::Mat(4, 5, CV_64F), mask, "test"), InvalidInput);
  EXPECT_THROW(check_inpaint_arguments(cv::Mat(4, 5, CV_32FC3), mask, "test"), InvalidInput);
  EXPECT_THROW(check_inpaint_arguments(cv::Mat(4, 5, CV_16U), mask, "test"), InvalidInput);
  EXPECT_THROW(check_inpaint_arguments(depth, cv::Mat(4, 5, CV_16U), "test"), InvalidInput);
  EXPECT_THROW(check_inpaint_arguments(depth, cv::Mat(4, 5, CV_8UC3), "test"), InvalidInput);
  EXPECT_THROW(check_inpaint_arguments(depth, cv::Mat(5, 4, CV_8U), "test"), InvalidInput);
  EXPECT_THROW(check_inpaint_arguments(depth, cv::Mat(4, 6, CV_8U), "test"), InvalidInput);
  try {
    check_inpaint_arguments(depth, cv::Mat(4, 6, CV_8U), "stage x");
    FAIL() << "no exception";
  } catch (const InvalidInput& error) {
    EXPECT_EQ(std::string(error.what()).rfind("stage x", 0), 0u) << error.what();
  }
  for (const std::string& name : inpainter_names()) {
    cv::Mat out;
    EXPECT_THROW(make_inpainter(name)->inpaint(cv::Mat(4, 5, CV_64F), mask, out), InvalidInput);
    EXPECT_THROW(make_inpainter(name)->inpaint(depth, cv::Mat(3, 5, CV_8U), out), InvalidInput);
  }
}

// Pixels outside the mask come back bit for bit (Telea's 16-bit round trip included), the output
// is CV_32FC1 of the input's size, masked pixels holding NaN do not leak, and an empty mask
// returns the input.
TEST(Inpaint, KnownPixelsAreReturnedBitIdentical) {
  cv::Mat depth(24, 31, CV_32F);
  cv::RNG random(12345);
  random.fill(depth, cv::RNG::UNIFORM, -3.0, 7.0);
  cv::Mat mask = cv::Mat::zeros(depth.size(), CV_8U);
  cv::circle(mask, {12, 10}, 5, 255, -1);
  mask(cv::Rect(0, 0, 3, 2)).setTo(255);  // on the top-left border too
  depth.setTo(std::nanf(""), mask);
  for (const std::string& name : inpainter_names()) {
    cv::Mat out;
    make_inpainter(name)->inpaint(depth, mask, out);
    ASSERT_EQ(out.type(), CV_32FC1) << name;
    ASSERT_EQ(out.size(), depth.size()) << name;
    int different = 0, not_finite = 0;
    for (int row = 0; row < depth.rows; ++row) {
      for (int col = 0; col < depth.cols; ++col) {
        const float a = depth.at<float>(row, col), b = out.at<float>(row, col);
        if (mask.at<std::uint8_t>(row, col)) {
          not_finite += !std::isfinite(b);
          // Within the known range for weighted means; mls fits quadratics, and an FoE MAP has no
          // maximum principle (on this noise Roth & Black's prior lowers E by overshooting it).
          if (name != "mls" && name != "foe") {
            EXPECT_GE(b, -3.0f) << name;
            EXPECT_LE(b, 7.0f) << name;
          }
        } else {
          different += std::memcmp(&a, &b, sizeof(float)) != 0;
        }
      }
    }
    EXPECT_EQ(different, 0) << name;
    EXPECT_EQ(not_finite, 0) << name;

    cv::Mat untouched;
    make_inpainter(name)->inpaint(depth, cv::Mat::zeros(depth.size(), CV_8U), untouched);
    EXPECT_EQ(std::memcmp(untouched.data, depth.data, depth.total() * sizeof(float)), 0) << name;
  }
}

// opencv#25404 (fixed in 4.10): INPAINT_TELEA on CV_32F adds a +0.5 rounding bias and a gradient
// term of up to ±√2 per pixel. A constant 0.25 image with a masked rectangle away from the border
// comes back from raw cv::inpaint up to about 2 off; the wrapper (Telea on CV_16U) returns 0.25.
TEST(OpenCvWorkarounds, TeleaOnFloatImagesIsExact_opencv25404) {
  cv::Mat depth(20, 20, CV_32F, cv::Scalar(0.25)), mask = cv::Mat::zeros(20, 20, CV_8U);
  mask(cv::Rect(6, 7, 6, 5)).setTo(255);

  for (const std::string& name : inpainter_names()) {
    cv::Mat out;
    make_inpainter(name)->inpaint(depth, mask, out);
    EXPECT_LE(max_error_in(out, 0.25, mask), 1e-6) << name;
  }

  // Whether the workaround is still needed: said, not asserted (a fixed OpenCV is no failure).
  cv::Mat raw;
  cv::inpaint(depth, mask, raw, 5, cv::INPAINT_TELEA);
  if (!(max_error_in(raw, 0.25, mask) > 1.0)) {
    GTEST_SKIP() << "this OpenCV no longer has bug #25404: the CV_16U workaround could go";
  }
}

// opencv#25389 (fixed in 4.10): both methods mishandle masked pixels on the top or left border.
// A 5×5 image of 0.25 whose top-left 3×3 block is masked (and holds 0, as unknown depth does in a
// range image) comes back constant from the wrapper; raw cv::inpaint is far off there, while the
// same block in the bottom-right corner comes back right (up to Telea's integer rounding).
TEST(OpenCvWorkarounds, MaskOnTheTopLeftBorderIsRestored_opencv25389) {
  auto corner_image = [](int type, double value, cv::Rect block, cv::Mat& mask) {
    cv::Mat image(5, 5, type, cv::Scalar(value));
    mask = cv::Mat::zeros(5, 5, CV_8U);
    mask(block).setTo(255);
    image.setTo(0, mask);
    return image;
  };
  const cv::Rect top_left(0, 0, 3, 3), bottom_right(2, 2, 3, 3);
  cv::Mat mask;
  const cv::Mat depth = corner_image(CV_32F, 0.25, top_left, mask);
  for (const std::string& name : inpainter_names()) {
    cv::Mat out;
    make_inpainter(name)->inpaint(depth, mask, out);
    EXPECT_LE(max_error_in(out, 0.25, mask), 1e-4) << name;
  }

  // The same block in the bottom-right corner comes back right from raw cv::inpaint.
  cv::Mat raw, fine_mask;
  cv::inpaint(corner_image(CV_32F, 0.25, bottom_right, fine_mask), fine_mask, raw, 5,
              cv::INPAINT_NS);
  EXPECT_LE(max_error_in(raw, 0.25, fine_mask), 1e-6);
  cv::inpaint(corner_image(CV_16U, 60000, bottom_right, fine_mask), fine_mask, raw, 5,
              cv::INPAINT_TELEA);
  EXPECT_LE(max_error_in(raw, 60000, fine_mask), 2);

  // Whether the padding is still needed, said, not asserted: raw Navier–Stokes on the float image
  // reads the masked zeros, and raw Telea on CV_16U falls far short of 60000.
  cv::inpaint(depth, mask, raw, 5, cv::INPAINT_NS);
  const bool ns_bug = max_error_in(raw, 0.25, mask) > 0.1;
  cv::inpaint(corner_image(CV_16U, 60000, top_left, mask), mask, raw, 5, cv::INPAINT_TELEA);
  const bool telea_bug = max_error_in(raw, 60000, mask) > 1000;
  if (!ns_bug && !telea_bug) {
    GTEST_SKIP() << "this OpenCV no longer has bug #25389: the padding could go";
  }
}

// A linear ramp (0.02 per column, −0.01 per row) with a disk of radius 7 masked. Telea and
// Navier–Stokes are weighted means of the rim at heart, so they do not reproduce a gradient
// exactly (the ramp changes by 0.31 across the disk; this is why repair() removes a trend first).
// The tolerances on the worst and the mean error, 0.12 and 0.06, leave room for that and fail on
// a bias such as #25404's (about 2), a lost scale or a fill that ignores one side of the rim; and
// the fill must stay within the rim's range (a weighted mean cannot leave it).
TEST(Inpaint, LinearRampIsReproducedApproximately) {
  cv::Mat depth(40, 40, CV_32F), mask = cv::Mat::zeros(40, 40, CV_8U);
  for (int row = 0; row < 40; ++row) {
    for (int col = 0; col < 40; ++col) depth.at<float>(row, col) = 0.3f + 0.02f * col - 0.01f * row;
  }
  cv::circle(mask, {20, 18}, 7, 255, -1);
  cv::Mat ring;
  cv::dilate(mask, ring, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}));
  ring &= ~mask;
  double ring_low = 0, ring_high = 0;
  cv::minMaxLoc(depth, &ring_low, &ring_high, nullptr, nullptr, ring);
  for (const std::string& name : inpainter_names()) {
    cv::Mat out;
    make_inpainter(name)->inpaint(depth, mask, out);
    double worst = 0, sum = 0;
    for (int row = 0; row < 40; ++row) {
      for (int col = 0; col < 40; ++col) {
        if (!mask.at<std::uint8_t>(row, col)) continue;
        const double value = out.at<float>(row, col);
        const double error = std::abs(value - depth.at<float>(row, col));
        worst = std::max(worst, error);
        sum += error;
        EXPECT_GE(value, ring_low - 1e-6) << name;
        EXPECT_LE(value, ring_high + 1e-6) << name;
      }
    }
    EXPECT_LT(worst, 0.12) << name;
    EXPECT_LT(sum / cv::countNonZero(mask), 0.06) << name;
  }
}

}  // namespace
}  // namespace rangefill

namespace rangefill {
namespace {

// The 5-point Laplacian of x² − y² is zero: the harmonic fill reproduces it to rounding.
TEST(Harmonic, ReproducesAHarmonicFunction) {
  const int n = 41;
  cv::Mat image(n, n, CV_32F), mask = cv::Mat::zeros(n, n, CV_8U);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      const double x = (c - 20) / 20.0, y = (r - 20) / 20.0;
      image.at<float>(r, c) = static_cast<float>(x * x - y * y);
      if (x * x + y * y < 0.25) mask.at<std::uint8_t>(r, c) = 255;
    }
  }
  cv::Mat input = image.clone(), out;
  input.setTo(0, mask);
  make_inpainter("harmonic")->inpaint(input, mask, out);
  double worst = 0;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      if (mask.at<std::uint8_t>(r, c)) {
        worst = std::max(worst, std::abs(out.at<float>(r, c) - image.at<float>(r, c)) * 1.0);
      }
    }
  }
  EXPECT_LT(worst, 1e-5);
}

// Neumann at the border: a mask reaching the image edge is filled by the known side alone.
TEST(Harmonic, BorderIsAFreeEdge) {
  cv::Mat image(8, 8, CV_32F, cv::Scalar(3)), mask = cv::Mat::zeros(8, 8, CV_8U), out;
  mask(cv::Rect(0, 4, 8, 4)) = 255;  // the lower half, down to the border
  make_inpainter("harmonic")->inpaint(image, mask, out);
  for (int r = 4; r < 8; ++r) {
    for (int c = 0; c < 8; ++c) EXPECT_NEAR(out.at<float>(r, c), 3.0f, 1e-6);
  }
  mask.setTo(255);  // nothing known
  make_inpainter("harmonic")->inpaint(image, mask, out);
  EXPECT_EQ(cv::countNonZero(out), 0);
}

// Guided, the membrane bends at the guide's edge: a strip known as 0 on its left end and 1 on its
// right, its guide dark left of column 10 and light from there, fills with about 0 left of the edge
// and about 1 right of it, where the unguided fill is the straight ramp between.
TEST(Harmonic, AGuideEdgePartsTheFill) {
  const int width = 21;
  cv::Mat image(3, width, CV_32F, cv::Scalar(0)), mask(3, width, CV_8U, cv::Scalar(255));
  image.col(width - 1).setTo(1);
  mask.col(0).setTo(0);
  mask.col(width - 1).setTo(0);
  cv::Mat guide(3, width, CV_32FC3, cv::Scalar(20, 20, 20));
  guide.colRange(10, width).setTo(cv::Scalar(220, 220, 220));
  cv::Mat plain, guided;
  HarmonicInpainter().inpaint(image, mask, plain);
  HarmonicInpainter(guide, 10).inpaint(image, mask, guided);
  EXPECT_NEAR(plain.at<float>(1, 9), 0.45, 1e-4);
  EXPECT_NEAR(plain.at<float>(1, 10), 0.5, 1e-4);
  EXPECT_LT(guided.at<float>(1, 9), 0.02);
  EXPECT_GT(guided.at<float>(1, 10), 0.98);
  EXPECT_THROW(
      HarmonicInpainter(guide, 10).inpaint(image.colRange(0, 20), mask.colRange(0, 20), guided),
      InvalidInput);
  EXPECT_THROW(HarmonicInpainter(cv::Mat(3, width, CV_8UC3), 10), InvalidInput);
}

}  // namespace
}  // namespace rangefill
