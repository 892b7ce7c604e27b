#include "rangefill/core/geometry2d.h"

#include <gtest/gtest.h>

namespace rangefill {
namespace {

TEST(Geometry2d, OrientationIsTwiceTheSignedArea) {
  EXPECT_DOUBLE_EQ(orient2d({0, 0}, {2, 0}, {0, 3}), 6);
  EXPECT_DOUBLE_EQ(orient2d({0, 0}, {0, 3}, {2, 0}), -6);
  EXPECT_DOUBLE_EQ(orient2d({0, 0}, {1, 1}, {2, 2}), 0);
}

// Crossing, touching at an end, collinear overlap and meeting end to end touch; parallel,
// collinear apart and passing near do not.
TEST(Geometry2d, SegmentsTouchIncludesEndsAndOverlaps) {
  EXPECT_TRUE(segments_touch({0, 0}, {2, 2}, {0, 2}, {2, 0}));
  EXPECT_TRUE(segments_touch({0, 0}, {2, 0}, {1, 0}, {1, 5}));
  EXPECT_TRUE(segments_touch({0, 0}, {2, 0}, {1, 0}, {3, 0}));
  EXPECT_TRUE(segments_touch({0, 0}, {1, 0}, {1, 0}, {1, 1}));
  EXPECT_FALSE(segments_touch({0, 0}, {2, 0}, {0, 1}, {2, 1}));
  EXPECT_FALSE(segments_touch({0, 0}, {1, 0}, {2, 0}, {3, 0}));
  EXPECT_FALSE(segments_touch({0, 0}, {2, 0}, {1, 0.001}, {1, 5}));
}

TEST(Geometry2d, DistanceToSegmentClampsToItsEnds) {
  EXPECT_DOUBLE_EQ(distance_to_segment({1, 3}, {0, 0}, {2, 0}), 3);
  EXPECT_DOUBLE_EQ(distance_to_segment({5, 4}, {0, 0}, {2, 0}), 5);
  EXPECT_DOUBLE_EQ(distance_to_segment({3, 4}, {0, 0}, {0, 0}), 5);  // a point
}

TEST(Geometry2d, PolygonAreaIsSignedByOrientation) {
  const std::vector<Vec2> square = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  EXPECT_DOUBLE_EQ(polygon_area(square), 4);
  EXPECT_DOUBLE_EQ(polygon_area({square.rbegin(), square.rend()}), -4);
  EXPECT_DOUBLE_EQ(polygon_area({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}}), 6);  // an L
}

}  // namespace
}  // namespace rangefill
