// Complex holes (complex_hole.h, Section VI-C): loops made from vertex lists, and the parts into
// which a hole whose projection is not simple is split.
#include "rangefill/complex_hole.h"

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
// edge and whose projection is simple, measured like make_loop, with the hole's id.
void expect_valid_parts(const Mesh& mesh, const MeshTopology& topology, const BoundaryLoop& hole,
                        const Frame& frame, const std::vector<BoundaryLoop>& parts) {
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
    EXPECT_TRUE(is_simple_polygon(project_loop(mesh, part, frame)));
    const BoundaryLoop measured = make_loop(mesh, hole.id, part.vertices);
    EXPECT_DOUBLE_EQ(part.perimeter, measured.perimeter);
    EXPECT_DOUBLE_EQ(part.area, measured.area);
  }
}

// Seen along z, each loop of the ribbon crosses itself once: the split cuts it at the crossing and
// keeps a lobe, a run of about half the loop that projects simply.
TEST(SplitComplexHole, FigureEightIsCutIntoASimpleLobe) {
  const Mesh mesh = figure_eight_ribbon(64);
  const MeshTopology topology = build_topology(mesh);
  ASSERT_EQ(topology.nonmanifold_edge_count + topology.misoriented_edge_count, 0);
  const HoleSet holes = find_holes(mesh, topology);
  ASSERT_EQ(holes.loops.size(), 2u);
  const Frame frame;  // looking down z
  for (const BoundaryLoop& hole : holes.loops) {
    SCOPED_TRACE("loop " + std::to_string(hole.id));
    ASSERT_EQ(hole.vertices.size(), 64u);
    ASSERT_FALSE(is_simple_polygon(project_loop(mesh, hole, frame)));
    const std::vector<BoundaryLoop> parts = split_complex_hole(mesh, topology, hole, frame);
    ASSERT_FALSE(parts.empty());
    expect_valid_parts(mesh, topology, hole, frame, parts);
    // A lobe holds about half of the 64 vertices (the cut drops a few round the crossing).
    EXPECT_GE(parts[0].vertices.size(), 24u);
    EXPECT_LE(parts[0].vertices.size(), 34u);
  }
}

// A hole that projects simply with its whole rim facing the viewer is not complex: no part (the
// only simple run is the whole loop, which a part may not be).
TEST(SplitComplexHole, SimpleHoleHasNoParts) {
  const Mesh sheet = testing::remove_faces(
      testing::make_grid(12), [](const Vec3& p) { return (p - Vec3(6, 6, 0)).norm() < 3.5; });
  const MeshTopology topology = build_topology(sheet);
  for (const BoundaryLoop& hole : find_holes(sheet, topology).loops) {
    EXPECT_TRUE(split_complex_hole(sheet, topology, hole, Frame()).empty()) << hole.id;
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
  BoundaryLoop hole;
  for (const BoundaryLoop& loop : find_holes(sheet, topology).loops) {
    if (!loop.longest_in_component) hole = loop;
  }
  ASSERT_EQ(hole.vertices.size(), 24u);
  const std::vector<BoundaryLoop> parts = split_complex_hole(sheet, topology, hole, Frame());
  ASSERT_FALSE(parts.empty());
  expect_valid_parts(sheet, topology, hole, Frame(), parts);
  const bool near_side = std::any_of(parts.begin(), parts.end(), [&](const BoundaryLoop& part) {
    return part.vertices.size() == 13 &&
           std::all_of(part.vertices.begin(), part.vertices.end(),
                       [&](int v) { return sheet.positions[v].z() == 0; });
  });
  EXPECT_TRUE(near_side);
}

}  // namespace
}  // namespace rangefill
