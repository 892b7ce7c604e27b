#include "rangefill/repair/fill.h"

#include <gtest/gtest.h>

#include "rangefill/core/topology.h"
#include "rangefill/repair/holes.h"
#include "support.h"

namespace rangefill {
namespace {

// A tent over a loop: its vertices joined to one point.
Fill tent(const BoundaryLoop& loop, const Vec3& apex) {
  Fill fill;
  fill.boundary = loop.vertices;
  fill.points = {apex};
  const int n = static_cast<int>(loop.vertices.size());
  for (int k = 0; k < n; ++k) fill.triangles.push_back({k, (k + 1) % n, n});
  return fill;
}

// Two square holes side by side in a flat sheet, each fill made without the other: tents leaning
// over each other's hole cross; upright tents do not; a fill meets itself only where it is.
TEST(FillsIntersect, FindsFillsOfTwoHolesThatMeet) {
  const Mesh sheet = testing::remove_faces(testing::make_grid(20), [](const Vec3& p) {
    return p.y() >= 6 && p.y() <= 12 &&
           ((p.x() >= 4 && p.x() <= 8) || (p.x() >= 10 && p.x() <= 14));
  });
  const HoleSet holes = find_holes(sheet, build_topology(sheet));
  const BoundaryLoop *left = nullptr, *right = nullptr;
  for (const BoundaryLoop& loop : holes.loops) {
    if (loop.vertices.size() != 20) continue;  // not the sheet's border
    (sheet.positions[loop.vertices[0]].x() < 9 ? left : right) = &loop;
  }
  ASSERT_TRUE(left && right);
  EXPECT_TRUE(fills_intersect(sheet, tent(*left, {11, 9, 2}), tent(*right, {6, 9, 2})));
  EXPECT_FALSE(fills_intersect(sheet, tent(*left, {6, 9, 1}), tent(*right, {12, 9, 1})));
  EXPECT_FALSE(fills_intersect(sheet, tent(*left, {6, 9, 1}), tent(*right, {12, 9, -1})));
}

TEST(Refusal, HasANameAndWords) {
  EXPECT_EQ(refusal_name(Refusal::intersects), "intersects");
  EXPECT_EQ(refusal_text(Refusal::intersects), "the fill would intersect the surface or itself");
}

}  // namespace
}  // namespace rangefill
