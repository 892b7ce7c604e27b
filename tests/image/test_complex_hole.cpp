// Complex holes (complex_hole.h, Section VI-C): loops made from vertex lists, and the parts into
// which a hole whose projection is not simple is split.
#include "rangefill/image/complex_hole.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "support.h"

namespace rangefill {
namespace {

// make_loop measures the closed polygon over the listed vertices, the closing chord included:
// perimeter and |vector area| (exact for a planar loop, wherever it lies).
TEST(MakeLoop, MeasuresPerimeterAndAreaWithTheChord) {
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, -1).normalized()).toRotationMatrix();
  const Vec3 shift(5, -3, 2);
  std::vector<Vec3> corners = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, {7, 7, 7}};
  for (Vec3& p : corners) p = rotation * p + shift;
  const Mesh mesh = make_mesh(corners, {});

  const BoundaryLoop rectangle = make_loop(mesh, 7, {0, 1, 2, 3});
  EXPECT_EQ(rectangle.id, 7);
  EXPECT_EQ(rectangle.vertices, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_NEAR(rectangle.perimeter, 6, 1e-12);
  EXPECT_NEAR(rectangle.area, 2, 1e-12);

  const BoundaryLoop triangle = make_loop(mesh, 1, {0, 1, 2});  // chord 2 → 0 of length √5
  EXPECT_NEAR(triangle.perimeter, 3 + std::sqrt(5.0), 1e-12);
  EXPECT_NEAR(triangle.area, 1, 1e-12);
  // Order does not change the size of the vector area; its sign is lost in the norm.
  EXPECT_NEAR(make_loop(mesh, 1, {3, 2, 1, 0}).area, 2, 1e-12);
}

// A ribbon of width 0.1 along a lemniscate of Gerono (x, y) = (cos t, sin t cos t) lifted by
// z = 0.5 sin t, so that the two branches pass 1 apart in z where they cross in projection: an
// annulus whose two boundary loops are each a figure eight seen along z.
Mesh figure_eight_ribbon(int samples) {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  for (int k = 0; k < samples; ++k) {
    const double t = 2 * M_PI * k / samples;
    const Vec3 centre(std::cos(t), std::sin(t) * std::cos(t), 0.5 * std::sin(t));
    const Vec3 tangent(-std::sin(t), std::cos(2 * t), 0);
    const Vec3 side = Vec3(-tangent.y(), tangent.x(), 0).normalized() * 0.05;
    positions.push_back(centre - side);
    positions.push_back(centre + side);
  }
  for (int k = 0; k < samples; ++k) {
    const int a = 2 * k, b = 2 * k + 1, c = 2 * ((k + 1) % samples), d = c + 1;
    triangles.push_back({a, c, d});
    triangles.push_back({a, d, b});
  }
  return make_mesh(positions, triangles);
}

// Checks what split_complex_hole promises of each part: a run of the hole's loop (contiguous, in
// loop order, wrapping round) of at least 3 and fewer than all vertices, whose chord is not a mesh
// edge, measured like make_loop, with the hole's id.
void expect_valid_parts(const Mesh& mesh, const MeshTopology& topology, const BoundaryLoop& hole,
                        const std::vector<BoundaryLoop>& parts) {
  const int n = static_cast<int>(hole.vertices.size());
  for (const BoundaryLoop& part : parts) {
    const int m = static_cast<int>(part.vertices.size());
    EXPECT_GE(m, 3);
    EXPECT_LT(m, n);
    EXPECT_EQ(part.id, hole.id);
    const auto start = std::find(hole.vertices.begin(), hole.vertices.end(), part.vertices[0]);
    ASSERT_NE(start, hole.vertices.end());
    const int offset = static_cast<int>(start - hole.vertices.begin());
    for (int k = 0; k < m; ++k) {
      EXPECT_EQ(part.vertices[k], hole.vertices[(offset + k) % n]) << "not a run at " << k;
    }
    const int first = part.vertices.front(), last = part.vertices.back();
    EXPECT_LT(find_halfedge(mesh, topology, first, last), 0);
    EXPECT_LT(find_halfedge(mesh, topology, last, first), 0);
    const BoundaryLoop measured = make_loop(mesh, hole.id, part.vertices);
    EXPECT_DOUBLE_EQ(part.perimeter, measured.perimeter);
    EXPECT_DOUBLE_EQ(part.area, measured.area);
  }
}

// Seen along z, each loop of the ribbon crosses itself once: the split cuts it at the crossing and
// keeps a lobe, a run of about half the loop that projects simply (Fig. 12). The lobe's chord joins
// the two branches across the crossing; it leaves one loop away from the ribbon but the other over
// it, so only the first loop gets the lobe; both get the parts cut at necks.
TEST(SplitComplexHole, FigureEightIsCutIntoASimpleLobe) {
  const Mesh mesh = figure_eight_ribbon(64);
  const MeshTopology topology = build_topology(mesh);
  ASSERT_EQ(topology.nonmanifold_edge_count + topology.misoriented_edge_count, 0);
  const HoleSet holes = find_holes(mesh, topology);
  ASSERT_EQ(holes.loops.size(), 2u);
  const Frame frame;  // looking down z
  int lobes = 0;
  for (const BoundaryLoop& hole : holes.loops) {
    SCOPED_TRACE("loop " + std::to_string(hole.id));
    ASSERT_EQ(hole.vertices.size(), 64u);
    ASSERT_FALSE(is_simple_polygon(hole_in_plane(mesh, hole, frame).loop));
    const std::vector<BoundaryLoop> parts =
        split_complex_hole(mesh, topology, hole, hole_in_plane(mesh, hole, frame));
    ASSERT_FALSE(parts.empty());
    expect_valid_parts(mesh, topology, hole, parts);
    // A lobe holds about half of the 64 vertices (the cut drops a few round the crossing).
    const bool lobe = parts[0].vertices.size() >= 24 && parts[0].vertices.size() <= 34 &&
                      is_simple_polygon(hole_in_plane(mesh, parts[0], frame).loop);
    lobes += lobe;
  }
  EXPECT_EQ(lobes, 1);
}

// A round hole that no plane were to accept is cut across its middle: its two halves, each with
// about half the loop, share a chord about as long as the hole is wide.
TEST(SplitComplexHole, RoundHoleIsCutInHalves) {
  const Mesh sheet = testing::remove_faces(
      testing::make_grid(12), [](const Vec3& p) { return (p - Vec3(6, 6, 0)).norm() < 3.5; });
  const MeshTopology topology = build_topology(sheet);
  const BoundaryLoop hole = testing::inner_loop(sheet);
  ASSERT_FALSE(hole.vertices.empty());
  const std::vector<BoundaryLoop> parts =
      split_complex_hole(sheet, topology, hole, hole_in_plane(sheet, hole, Frame()));
  ASSERT_GE(parts.size(), 2u);
  expect_valid_parts(sheet, topology, hole, parts);
  EXPECT_EQ(parts[0].vertices.size() + parts[1].vertices.size(), hole.vertices.size() + 2);
  EXPECT_EQ(parts[0].vertices.front(), parts[1].vertices.back());
  EXPECT_EQ(parts[0].vertices.back(), parts[1].vertices.front());
  const double chord =
      (sheet.positions[parts[0].vertices.front()] - sheet.positions[parts[0].vertices.back()])
          .norm();
  EXPECT_GT(chord, 4);  // the jagged hole is 6 wide at most
}

// A slot 24 long and 2 wide is cut across, not along: the chord is short and the two sides hold
// about half the slot each.
TEST(SplitComplexHole, LongThinHoleIsCutAcrossItsMiddle) {
  const Mesh sheet = testing::remove_faces(testing::make_grid(30), [](const Vec3& p) {
    return p.x() >= 3 && p.x() <= 27 && p.y() >= 14 && p.y() <= 16;
  });
  const MeshTopology topology = build_topology(sheet);
  const BoundaryLoop hole = testing::inner_loop(sheet);
  ASSERT_EQ(hole.vertices.size(), 52u);
  const std::vector<BoundaryLoop> parts =
      split_complex_hole(sheet, topology, hole, hole_in_plane(sheet, hole, Frame()));
  ASSERT_GE(parts.size(), 2u);
  expect_valid_parts(sheet, topology, hole, parts);
  const Vec3 a = sheet.positions[parts[0].vertices.front()],
             b = sheet.positions[parts[0].vertices.back()];
  EXPECT_LE((a - b).norm(), std::sqrt(8.0));
  EXPECT_NEAR(a.x(), 15, 2);
  EXPECT_NEAR(b.x(), 15, 2);
  EXPECT_NEAR(static_cast<double>(parts[1].vertices.size()), 27, 3);
}

// A horseshoe hole round a peninsula of surface: the shortest chords run across the peninsula,
// between the arms, but a chord must leave into the hole at both ends, so none of the parts' chords
// crosses the peninsula.
TEST(SplitComplexHole, ChordsNeverCrossTheSurface) {
  auto peninsula = [](const Vec3& p) { return p.x() > 9 && p.x() < 11 && p.y() < 13; };
  const Mesh sheet = testing::remove_faces(testing::make_grid(20), [&](const Vec3& p) {
    return p.x() >= 4 && p.x() <= 16 && p.y() >= 4 && p.y() <= 16 && !peninsula(p);
  });
  const MeshTopology topology = build_topology(sheet);
  const BoundaryLoop hole = testing::inner_loop(sheet);
  ASSERT_FALSE(hole.vertices.empty());
  const std::vector<BoundaryLoop> parts =
      split_complex_hole(sheet, topology, hole, hole_in_plane(sheet, hole, Frame()));
  ASSERT_FALSE(parts.empty());
  expect_valid_parts(sheet, topology, hole, parts);
  for (const BoundaryLoop& part : parts) {
    const Vec3 a = sheet.positions[part.vertices.front()],
               b = sheet.positions[part.vertices.back()];
    for (int k = 1; k < 100; ++k) {
      EXPECT_FALSE(peninsula(a + (b - a) * (k / 100.0)))
          << "chord " << a.transpose() << " - " << b.transpose();
    }
  }
}

// A hole across a 120° fold of a grid, seen along the near side's normal: the rim beyond the fold
// is seen from behind (and its projection runs back over the near side's), so one of the parts is
// the run of the rim on the near side, closed by a chord along the fold.
TEST(SplitComplexHole, RimSeenFromBehindIsLeftOut) {
  Mesh sheet = testing::remove_faces(testing::make_grid(16), [](const Vec3& p) {
    return p.x() >= 5 && p.x() <= 11 && p.y() >= 5 && p.y() <= 11;
  });
  const double angle = 120 * M_PI / 180;
  for (Vec3& p : sheet.positions) {
    if (p.x() > 8)
      p = Vec3(8 + (p.x() - 8) * std::cos(angle), p.y(), (p.x() - 8) * std::sin(angle));
  }
  const MeshTopology topology = build_topology(sheet);
  const BoundaryLoop hole = testing::inner_loop(sheet);
  ASSERT_EQ(hole.vertices.size(), 24u);
  const std::vector<BoundaryLoop> parts =
      split_complex_hole(sheet, topology, hole, hole_in_plane(sheet, hole, Frame()));
  ASSERT_FALSE(parts.empty());
  expect_valid_parts(sheet, topology, hole, parts);
  const bool near_side = std::any_of(parts.begin(), parts.end(), [&](const BoundaryLoop& part) {
    return part.vertices.size() == 13 &&
           std::all_of(part.vertices.begin(), part.vertices.end(),
                       [&](int v) { return sheet.positions[v].z() == 0; });
  });
  EXPECT_TRUE(near_side);
}

}  // namespace
}  // namespace rangefill
