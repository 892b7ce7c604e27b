// Range images (range_image.h): rasterisation and normalisation (eq. 6–8), the inverse mapping
// (eq. 13), the hole mask, small-gap filling (Section VI-B, eq. 9–10) and rim support.
#include "rangefill/image/range_image.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "support.h"

namespace rangefill {
namespace {

using testing::make_grid;
using testing::remove_faces;

int count_label(const RangeImage& image, PixelLabel label) {
  return cv::countNonZero(image.labels == label);
}

// A 30×30 grid, rotated and moved, without the faces inside a disk of radius 6; the zone is every
// face of it.
// A 30×30 sheet, tilted and moved, with a hole of radius 6 in its middle.
testing::TiltedSheet tilted_sheet() {
  return testing::make_tilted_sheet(
      30, Eigen::AngleAxisd(0.8, Vec3(2, -1, 0.4).normalized()).toRotationMatrix(), Vec3(4, 1, -6),
      Vec3(15, 15, 0), 6);
}

// Seen exactly along its normal, a flat zone has one depth: eq. 8 falls back to f_esc = 1 / q,
// every known pixel normalises to 0 (eq. 7), d_i is the sheet's depth in the frame, and eq. 13
// maps every known pixel back onto the sheet.
TEST(RasterizeZone, FlatSheetSeenAlongItsNormalHasOneDepth) {
  const testing::TiltedSheet sheet = tilted_sheet();
  Frame frame;
  frame.rotation = sheet.rotation.transpose();                    // rows: the sheet's axes
  frame.origin = sheet.shift + sheet.rotation * Vec3(12, 17, 3);  // 3 above the sheet
  const double mean_edge = mean_edge_length(sheet.mesh);
  const RangeImage image = rasterize_zone(sheet.mesh, sheet.zone, sheet.hole,
                                          hole_in_plane(sheet.mesh, sheet.hole, frame), mean_edge);
  const double q = 0.87 * mean_edge;  // eq. 6 with the default β
  EXPECT_DOUBLE_EQ(image.step, q);
  EXPECT_DOUBLE_EQ(image.depth_scale, 1 / q);
  EXPECT_NEAR(image.depth_offset, -3, 1e-12 * sheet.size);
  ASSERT_GT(count_label(image, kKnownPixel), 700);
  for (int row = 0; row < image.depth.rows; ++row) {
    for (int col = 0; col < image.depth.cols; ++col) {
      if (image.labels.at<std::uint8_t>(row, col) != kKnownPixel) continue;
      const float value = image.depth.at<float>(row, col);
      ASSERT_LE(std::abs(value), 1e-9) << "pixel " << row << ", " << col;
      const Vec3 local = image.local_point(row, col, value);
      EXPECT_DOUBLE_EQ(local.x(), image.x_min + col * q);
      EXPECT_DOUBLE_EQ(local.y(), image.y_max - row * q);
      ASSERT_LE(sheet.distance(frame.to_world(local)), 1e-9 * sheet.size);
    }
  }
}

// Seen at an angle, depth varies: eq. 7–8 map the known depths onto [0, 1] exactly, and eq. 13
// still puts every known pixel on the sheet (to float precision of the normalised depth).
TEST(RasterizeZone, TiltedViewNormalisesDepthAndMapsBackOntoTheSheet) {
  const testing::TiltedSheet sheet = tilted_sheet();
  Frame frame;
  frame.rotation =
      (sheet.rotation * Eigen::AngleAxisd(0.4, Vec3(1, 1, 0).normalized()).toRotationMatrix())
          .transpose();
  frame.origin = sheet.shift;
  const RangeImage image = rasterize_zone(sheet.mesh, sheet.zone, sheet.hole,
                                          hole_in_plane(sheet.mesh, sheet.hole, frame), 1.0);
  double lowest = 1, highest = 0, range = 0;
  for (int row = 0; row < image.depth.rows; ++row) {
    for (int col = 0; col < image.depth.cols; ++col) {
      if (image.labels.at<std::uint8_t>(row, col) != kKnownPixel) continue;
      const float value = image.depth.at<float>(row, col);
      lowest = std::min<double>(lowest, value);
      highest = std::max<double>(highest, value);
      const Vec3 world = frame.to_world(image.local_point(row, col, value));
      range = 1 / image.depth_scale;
      ASSERT_LE(sheet.distance(world), 1e-6 * range) << "pixel " << row << ", " << col;
    }
  }
  EXPECT_EQ(lowest, 0);
  EXPECT_EQ(highest, 1);
  EXPECT_GT(range, 5);  // the view is 0.4 rad off: a real depth range
}

// An axis-aligned grid of step 1 without the 8×8 square [5, 13]², seen from +z on a grid of step
// q = 0.4 (β = 0.4, d_m passed as 1). The zone spans [0, 20]², so x_min = −0.8, y_max = 20.8 and
// the image is ceil(20 / 0.4) + 2·2 + 1 = 55 pixels wide and high. Pixel centres x = −0.8 + 0.4 c
// fall inside (5, 13) for c = 15..34 and y = 20.8 − 0.4 r for r = 20..39: a 20×20 mask, no centre
// on the hole's edges. The zone leaves out the faces in [1, 3] × [15, 17] (edges again half a
// pixel from the centres): a gap of the 5×5 centres c = 5..9, r = 10..14.
TEST(RasterizeZone, HoleMaskIsThePixelsInsideTheProjectedLoop) {
  const Mesh mesh = remove_faces(make_grid(20), [](const Vec3& p) {
    return p.x() >= 5 && p.x() <= 13 && p.y() >= 5 && p.y() <= 13;
  });
  const BoundaryLoop hole = testing::inner_loop(mesh);
  ASSERT_EQ(hole.vertices.size(), 32u);
  Zone zone;
  for (int f = 0; f < mesh.face_count(); ++f) {
    const Triangle& t = mesh.triangles[f];
    const bool left_out = std::all_of(t.begin(), t.end(), [&](int v) {
      const Vec3& p = mesh.positions[v];
      return p.x() >= 1 && p.x() <= 3 && p.y() >= 15 && p.y() <= 17;
    });
    if (!left_out) zone.faces.push_back(f);
    for (int v : t) zone.vertices.push_back(v);
  }
  std::sort(zone.vertices.begin(), zone.vertices.end());
  zone.vertices.erase(std::unique(zone.vertices.begin(), zone.vertices.end()), zone.vertices.end());

  RangeImageOptions options;
  options.beta = 0.4;
  const RangeImage image =
      rasterize_zone(mesh, zone, hole, hole_in_plane(mesh, hole, Frame()), 1.0, options);
  ASSERT_EQ(image.depth.size(), cv::Size(55, 55));
  ASSERT_EQ(image.labels.size(), cv::Size(55, 55));
  EXPECT_NEAR(image.x_min, -0.8, 1e-12);
  EXPECT_NEAR(image.y_max, 20.8, 1e-12);
  EXPECT_EQ(image.depth_scale, 1 / 0.4);  // flat
  const cv::Mat mask = image.mask();
  EXPECT_EQ(mask.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(mask), 400);
  EXPECT_EQ(cv::countNonZero(mask(cv::Rect(15, 20, 20, 20))), 400);
  EXPECT_EQ(count_label(image, kGapPixel), 25);
  EXPECT_EQ(cv::countNonZero(image.labels(cv::Rect(5, 10, 5, 5)) == kGapPixel), 25);
  // Centres strictly inside (0, 20)² (c, r = 3..51) and not in the hole or the gap are known;
  // those beyond it (c, r < 2 or > 52) are outside. (Centres on the zone's border, c or r = 2 or
  // 52, lie exactly on its edges: covered or not by rounding.)
  for (int row = 0; row < 55; ++row) {
    for (int col = 0; col < 55; ++col) {
      const int label = image.labels.at<std::uint8_t>(row, col);
      if (row < 2 || row > 52 || col < 2 || col > 52) {
        EXPECT_EQ(label, kOutsidePixel) << row << ", " << col;
      } else if (row > 2 && row < 52 && col > 2 && col < 52 && label != kHolePixel &&
                 label != kGapPixel) {
        EXPECT_EQ(label, kKnownPixel) << row << ", " << col;
      }
    }
  }
  EXPECT_GE(count_label(image, kKnownPixel), 49 * 49 - 400 - 25);
}

// Images larger than max_pixels are refused before anything is allocated.
TEST(RasterizeZone, RefusesImagesOverThePixelLimit) {
  const testing::TiltedSheet sheet = tilted_sheet();
  Frame frame;
  frame.rotation = sheet.rotation.transpose();
  RangeImageOptions options;
  options.max_pixels = 100;
  EXPECT_THROW(rasterize_zone(sheet.mesh, sheet.zone, sheet.hole,
                              hole_in_plane(sheet.mesh, sheet.hole, frame), 1.0, options),
               ProcessingError);
}

// A hand-made image: every pixel known with value `value(row, col)` unless listed.
RangeImage hand_image(int rows, int cols, float (*value)(int, int)) {
  RangeImage image;
  image.depth = cv::Mat(rows, cols, CV_32F);
  image.labels = cv::Mat(rows, cols, CV_8U, cv::Scalar(kKnownPixel));
  image.step = 1;
  for (int row = 0; row < rows; ++row) {
    for (int col = 0; col < cols; ++col) image.depth.at<float>(row, col) = value(row, col);
  }
  return image;
}

float scattered(int row, int col) {  // distinct values, no pattern a mean could reproduce
  return static_cast<float>((row * 7 + col * 3) % 11) + 0.25f * row;
}

void set_label(RangeImage& image, int row, int col, PixelLabel label) {
  image.labels.at<std::uint8_t>(row, col) = label;
  if (label != kKnownPixel) image.depth.at<float>(row, col) = 0;
}

// Eq. 10: the mean of the listed pixels' current values, computed as fill_small_gaps does (sum in
// double, stored as float).
float mean_of(const RangeImage& image, std::initializer_list<std::pair<int, int>> pixels) {
  double sum = 0;
  for (auto [row, col] : pixels) sum += image.depth.at<float>(row, col);
  return static_cast<float>(sum / pixels.size());
}

// A single gap pixel takes the mean of its eight known neighbours and becomes known.
TEST(FillSmallGaps, SinglePixelTakesTheMeanOfItsNeighbours) {
  RangeImage image = hand_image(5, 5, scattered);
  set_label(image, 2, 2, kGapPixel);
  const float expected =
      mean_of(image, {{1, 1}, {1, 2}, {1, 3}, {2, 1}, {2, 3}, {3, 1}, {3, 2}, {3, 3}});
  const GapFillStats stats = fill_small_gaps(image);
  EXPECT_EQ(stats.areas, 1);
  EXPECT_EQ(stats.pixels, 1);
  EXPECT_EQ(stats.joined_to_hole, 0);
  EXPECT_EQ(image.depth.at<float>(2, 2), expected);
  EXPECT_EQ(image.labels.at<std::uint8_t>(2, 2), kKnownPixel);
}

// Eq. 9: inside an area, the pixel with the most filled neighbours goes first, ties by row then
// column. A 1×3 gap (2, 2..4): (2, 2) and (2, 4) have 7 known neighbours, (2, 3) has 6, so (2, 2)
// goes first; then (2, 3) and (2, 4) both have 7 and (2, 3) wins the tie; (2, 4) ends with 8.
TEST(FillSmallGaps, DiffusesInwardsMostFilledNeighboursFirst) {
  RangeImage image = hand_image(5, 7, scattered);
  for (int col = 2; col <= 4; ++col) set_label(image, 2, col, kGapPixel);
  RangeImage expected = image;
  expected.depth = image.depth.clone();
  expected.depth.at<float>(2, 2) =
      mean_of(expected, {{1, 1}, {1, 2}, {1, 3}, {2, 1}, {3, 1}, {3, 2}, {3, 3}});
  expected.depth.at<float>(2, 3) =
      mean_of(expected, {{1, 2}, {1, 3}, {1, 4}, {2, 2}, {3, 2}, {3, 3}, {3, 4}});
  expected.depth.at<float>(2, 4) =
      mean_of(expected, {{1, 3}, {1, 4}, {1, 5}, {2, 3}, {2, 5}, {3, 3}, {3, 4}, {3, 5}});
  const GapFillStats stats = fill_small_gaps(image);
  EXPECT_EQ(stats.areas, 1);
  EXPECT_EQ(stats.pixels, 3);
  for (int col = 2; col <= 4; ++col) {
    EXPECT_EQ(image.depth.at<float>(2, col), expected.depth.at<float>(2, col)) << "column " << col;
  }
}

// Areas are filled smallest first, and each pixel's value is the mean of its filled neighbours:
// a one-pixel area (2, 2) touches the two-pixel area (3, 3)–(3, 4) diagonally. (2, 2) goes first
// with its 7 known neighbours; then (3, 3) (7 filled neighbours, (2, 2) among them, tie with
// (3, 4) broken by column) and (3, 4) with 8.
TEST(FillSmallGaps, SmallestAreaFirstAndDiagonalNeighboursAveraged) {
  RangeImage image = hand_image(6, 7, scattered);
  set_label(image, 2, 2, kGapPixel);
  set_label(image, 3, 3, kGapPixel);
  set_label(image, 3, 4, kGapPixel);
  RangeImage expected = image;
  expected.depth = image.depth.clone();
  expected.depth.at<float>(2, 2) =
      mean_of(expected, {{1, 1}, {1, 2}, {1, 3}, {2, 1}, {2, 3}, {3, 1}, {3, 2}});
  expected.depth.at<float>(3, 3) =
      mean_of(expected, {{2, 2}, {2, 3}, {2, 4}, {3, 2}, {4, 2}, {4, 3}, {4, 4}});
  expected.depth.at<float>(3, 4) =
      mean_of(expected, {{2, 3}, {2, 4}, {2, 5}, {3, 3}, {3, 5}, {4, 3}, {4, 4}, {4, 5}});
  const GapFillStats stats = fill_small_gaps(image);
  EXPECT_EQ(stats.areas, 2);
  EXPECT_EQ(stats.pixels, 3);
  for (auto [row, col] : {std::pair{2, 2}, {3, 3}, {3, 4}}) {
    EXPECT_FLOAT_EQ(image.depth.at<float>(row, col), expected.depth.at<float>(row, col))
        << "pixel " << row << ", " << col;
  }
}

// A gap area that touches no known pixel (here: surrounded by hole pixels) joins the hole mask.
TEST(FillSmallGaps, GapWithoutKnownNeighbourJoinsTheHole) {
  RangeImage image = hand_image(7, 7, scattered);
  for (int row = 1; row <= 5; ++row) {
    for (int col = 1; col <= 5; ++col) set_label(image, row, col, kHolePixel);
  }
  set_label(image, 3, 3, kGapPixel);
  set_label(image, 3, 4, kGapPixel);
  const GapFillStats stats = fill_small_gaps(image);
  EXPECT_EQ(stats.areas, 0);
  EXPECT_EQ(stats.pixels, 0);
  EXPECT_EQ(stats.joined_to_hole, 2);
  EXPECT_EQ(image.labels.at<std::uint8_t>(3, 3), kHolePixel);
  EXPECT_EQ(image.labels.at<std::uint8_t>(3, 4), kHolePixel);
  EXPECT_EQ(cv::countNonZero(image.mask()), 25);
}

// Outside pixels take the value of the nearest known pixel: with known columns 2..4 between
// outside columns 0–1 and 5–6, each outside pixel copies the end of its own row.
TEST(FillSmallGaps, OutsidePixelsTakeTheNearestKnownValue) {
  RangeImage image = hand_image(5, 7, scattered);
  for (int row = 0; row < 5; ++row) {
    for (int col : {0, 1, 5, 6}) set_label(image, row, col, kOutsidePixel);
  }
  const cv::Mat before = image.depth.clone();
  const GapFillStats stats = fill_small_gaps(image);
  EXPECT_EQ(stats.areas, 0);
  for (int row = 0; row < 5; ++row) {
    EXPECT_EQ(image.depth.at<float>(row, 0), before.at<float>(row, 2)) << "row " << row;
    EXPECT_EQ(image.depth.at<float>(row, 1), before.at<float>(row, 2)) << "row " << row;
    EXPECT_EQ(image.depth.at<float>(row, 5), before.at<float>(row, 4)) << "row " << row;
    EXPECT_EQ(image.depth.at<float>(row, 6), before.at<float>(row, 4)) << "row " << row;
    for (int col = 2; col <= 4; ++col)
      EXPECT_EQ(image.depth.at<float>(row, col), before.at<float>(row, col));
    EXPECT_EQ(image.labels.at<std::uint8_t>(row, 0), kOutsidePixel);  // still outside
  }
}

// Rim support: the share of the pixels around the mask (8-neighbours outside it) that are known.
// A 3×3 mask in a known 7×7 image has a ring of 16: support 1. Making the ring's left column (5
// pixels) outside gives 11/16, one gap pixel more 10/16. An empty mask has support 1.
TEST(RimSupport, IsTheKnownShareOfTheRingAroundTheMask) {
  RangeImage image = hand_image(7, 7, scattered);
  EXPECT_EQ(rim_support(image), 1.0);
  for (int row = 2; row <= 4; ++row) {
    for (int col = 2; col <= 4; ++col) set_label(image, row, col, kHolePixel);
  }
  EXPECT_EQ(rim_support(image), 1.0);
  for (int row = 1; row <= 5; ++row) set_label(image, row, 1, kOutsidePixel);
  set_label(image, 3, 0, kOutsidePixel);  // not on the ring: no effect
  EXPECT_EQ(rim_support(image), 11.0 / 16);
  set_label(image, 1, 3, kGapPixel);
  EXPECT_EQ(rim_support(image), 10.0 / 16);
}

}  // namespace
}  // namespace rangefill
