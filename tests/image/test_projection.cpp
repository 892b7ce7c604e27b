// Projection planes (projection.h, geometry2d.h): simple polygons, the plane of a tilted sheet,
// separation between returned planes, and the visible part of a zone that folds over.
#include "rangefill/image/projection.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "support.h"

namespace rangefill {
namespace {

// A square is simple; so are a triangle and a non-convex L shape.
TEST(IsSimplePolygon, AcceptsSimplePolygons) {
  EXPECT_TRUE(is_simple_polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  EXPECT_TRUE(is_simple_polygon({{0, 0}, {1, 0}, {0, 1}}));
  EXPECT_TRUE(is_simple_polygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}));
  // Clockwise is as simple as counter-clockwise.
  EXPECT_TRUE(is_simple_polygon({{0, 0}, {0, 1}, {1, 1}, {1, 0}}));
}

// A bow-tie crosses itself; a repeated point, a vertex touching a non-adjacent edge, collinear
// overlapping edges and fewer than three points are all refused.
TEST(IsSimplePolygon, RefusesCrossingsTouchesAndRepeats) {
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {1, 1}, {1, 0}, {0, 1}}));  // bow-tie
  // (1, 1) twice, not consecutively: two lobes meeting at a point.
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {1, 1}, {2, 0}, {2, 2}, {1, 1}, {0, 2}}));
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {1, 0}, {1, 0}, {1, 1}, {0, 1}}));  // consecutive
  // Vertex (2, 0) lies inside the non-adjacent edge (0, 0)–(4, 0).
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}));
  // Edge (3, 0)–(1, 0) runs back along edge (0, 0)–(2, 0), which is not adjacent to it.
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {2, 0}, {3, 1}, {3, 0}, {1, 0}, {0, -1}}));
  EXPECT_FALSE(is_simple_polygon({{0, 0}, {1, 0}}));
}

// A 30×30 grid rotated and moved, with the faces inside a disk of radius 6 removed; its zone of
// interest grown over 5 rings.
struct TiltedSheet : testing::TiltedSheet {
  MeshTopology topology;
  HoleSet holes;
};

TiltedSheet tilted_sheet() {
  TiltedSheet sheet;
  static_cast<testing::TiltedSheet&>(sheet) = testing::make_tilted_sheet(
      30, Eigen::AngleAxisd(1.1, Vec3(0.3, -1, 0.6).normalized()).toRotationMatrix(),
      Vec3(-2, 5, 3), Vec3(15, 15, 0), 6);
  sheet.topology = build_topology(sheet.mesh);
  sheet.holes = find_holes(sheet.mesh, sheet.topology);
  ZoneOptions options;
  options.rings = 5;
  sheet.zone = grow_zone(sheet.mesh, sheet.topology, sheet.holes, sheet.hole, 1.0, options);
  return sheet;
}

// The best plane of a flat sheet is the sheet's own: its viewing direction is the faces' normal
// (the faces are seen from the front), the frame is a rotation, its origin the boundary's centroid
// and the hole projects as a simple polygon.
TEST(FindProjections, FlatSheetIsSeenAlongItsNormal) {
  const TiltedSheet sheet = tilted_sheet();
  ASSERT_EQ(sheet.holes.loops.size(), 2u);
  const ProjectionSearch search =
      find_projections(sheet.mesh, sheet.topology, sheet.zone, sheet.hole);
  ASSERT_FALSE(search.planes.empty());
  const Frame& frame = search.planes.front().plane.frame;
  EXPECT_GT(frame.normal().dot(sheet.normal()), 0.999);
  for (int face : sheet.zone.faces) {
    EXPECT_GT(triangle_cross(sheet.mesh, face).dot(frame.normal()), 0) << "face " << face;
  }
  EXPECT_NEAR((frame.rotation * frame.rotation.transpose() - Eigen::Matrix3d::Identity()).norm(), 0,
              1e-12);
  EXPECT_NEAR(frame.rotation.determinant(), 1, 1e-12);
  Vec3 centroid = Vec3::Zero();
  for (int v : sheet.hole.vertices) centroid += sheet.mesh.positions[v];
  centroid /= sheet.hole.vertices.size();
  EXPECT_NEAR((frame.origin - centroid).norm(), 0, 1e-12);
  EXPECT_TRUE(is_simple_polygon(hole_in_plane(sheet.mesh, sheet.hole, frame).loop));
  // Projected area: the zone's area times cos(angle to the normal), nothing folded.
  double area = 0;
  for (int face : sheet.zone.faces) area += 0.5 * triangle_cross(sheet.mesh, face).norm();
  EXPECT_GT(search.planes.front().projected_area, 0.999 * area);
  EXPECT_LE(search.planes.front().projected_area, area * (1 + 1e-12));
  EXPECT_EQ(search.planes.front().folded_area, 0);
}

// The planes returned are pairwise at least min_separation_degrees apart, best first.
TEST(FindProjections, ReturnedPlanesAreSeparated) {
  const TiltedSheet sheet = tilted_sheet();
  for (double separation : {10.0, 30.0}) {
    ProjectionOptions options;
    options.min_separation_degrees = separation;
    const ProjectionSearch search =
        find_projections(sheet.mesh, sheet.topology, sheet.zone, sheet.hole, options);
    ASSERT_EQ(search.planes.size(), 3u) << "separation " << separation;
    for (size_t i = 0; i < search.planes.size(); ++i) {
      for (size_t j = i + 1; j < search.planes.size(); ++j) {
        const double angle =
            std::acos(std::clamp(
                search.planes[i].plane.frame.normal().dot(search.planes[j].plane.frame.normal()),
                -1.0, 1.0)) *
            180 / M_PI;
        EXPECT_GE(angle, separation - 1e-9) << "planes " << i << " and " << j;
      }
      if (i > 0) {
        EXPECT_GE(search.planes[i - 1].projected_area, search.planes[i].projected_area);
      }
    }
  }
}

// A sheet that folds over, in profile (x, z) and extruded along y: A runs along z = 0 (facing
// +z), B turns back up at 135° (facing away from +z), C runs on above A (facing +z again).
struct FoldedSheet {
  Mesh mesh;
  std::vector<char> part;  // per face: 'A', 'B' or 'C'
};

FoldedSheet folded_sheet() {
  const int columns = 18, rows = 20;
  auto profile = [](int i) -> Vec2 {
    const double s = 1 / std::sqrt(2.0);
    if (i <= 10) return {double(i), 0.0};
    if (i <= 12) return {10 - (i - 10) * s, (i - 10) * s};
    return {10 - 2 * s + (i - 12), 2 * s};
  };
  std::vector<Vec3> positions;
  for (int y = 0; y <= rows; ++y) {
    for (int i = 0; i <= columns; ++i) positions.emplace_back(profile(i).x(), y, profile(i).y());
  }
  FoldedSheet sheet;
  std::vector<Triangle> triangles;
  auto id = [&](int i, int y) { return y * (columns + 1) + i; };
  for (int y = 0; y < rows; ++y) {
    for (int i = 0; i < columns; ++i) {
      // The hole: the quads with 3 <= i < 6 and 8 <= y < 12 of part A.
      if (i >= 3 && i < 6 && y >= 8 && y < 12) continue;
      triangles.push_back({id(i, y), id(i + 1, y), id(i + 1, y + 1)});
      triangles.push_back({id(i, y), id(i + 1, y + 1), id(i, y + 1)});
      const char part = i < 10 ? 'A' : i < 12 ? 'B' : 'C';
      sheet.part.push_back(part);
      sheet.part.push_back(part);
    }
  }
  sheet.mesh = make_mesh(positions, triangles);
  return sheet;
}

// visible_part keeps the faces that face the viewer and are connected to the rim through such
// faces: all of A; not B (seen from behind) nor C (facing the viewer, but reached only across B).
TEST(VisiblePart, KeepsFrontFacingFacesConnectedToTheRim) {
  const FoldedSheet sheet = folded_sheet();
  const MeshTopology topology = build_topology(sheet.mesh);
  const HoleSet holes = find_holes(sheet.mesh, topology);
  ASSERT_EQ(holes.loops.size(), 2u);
  const BoundaryLoop hole = testing::inner_loop(sheet.mesh);
  ASSERT_EQ(hole.vertices.size(), 14u);
  Zone zone;
  for (int f = 0; f < sheet.mesh.face_count(); ++f) zone.faces.push_back(f);
  for (int v = 0; v < sheet.mesh.vertex_count(); ++v) zone.vertices.push_back(v);
  zone.rings = 7;

  const Frame frame;  // identity: the viewer looks down from +z
  std::vector<int> expected, expected_vertices;
  for (int f = 0; f < sheet.mesh.face_count(); ++f) {
    const double facing = triangle_cross(sheet.mesh, f).dot(frame.normal());
    if (sheet.part[f] == 'B') {
      EXPECT_LT(facing, 0);
    } else {
      EXPECT_GT(facing, 0);  // C faces the viewer too
    }
    if (sheet.part[f] == 'A') {
      expected.push_back(f);
      for (int v : sheet.mesh.triangles[f]) expected_vertices.push_back(v);
    }
  }
  std::sort(expected_vertices.begin(), expected_vertices.end());
  expected_vertices.erase(std::unique(expected_vertices.begin(), expected_vertices.end()),
                          expected_vertices.end());
  const Zone visible = visible_part(sheet.mesh, topology, zone, hole, frame);
  EXPECT_EQ(visible.faces, expected);
  EXPECT_EQ(visible.vertices, expected_vertices);
  EXPECT_EQ(visible.rings, 7);  // the rest of the zone is kept

  // Seen from below, only B faces the viewer, and B does not touch the rim: nothing is left.
  Frame below;
  below.rotation = Eigen::AngleAxisd(M_PI, Vec3::UnitX()).toRotationMatrix().transpose();
  ASSERT_NEAR(below.normal().z(), -1, 1e-12);
  EXPECT_TRUE(visible_part(sheet.mesh, topology, zone, hole, below).faces.empty());
}

// project_loop gives the frame-local x, y of each loop vertex, in loop order.
TEST(ProjectLoop, GivesFrameLocalCoordinates) {
  const TiltedSheet sheet = tilted_sheet();
  Frame frame;
  frame.rotation = Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  frame.origin = Vec3(1, -1, 2);
  const std::vector<Vec2> points = hole_in_plane(sheet.mesh, sheet.hole, frame).loop;
  ASSERT_EQ(points.size(), sheet.hole.vertices.size());
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec3 local =
        frame.rotation * (sheet.mesh.positions[sheet.hole.vertices[k]] - frame.origin);
    EXPECT_EQ(points[k], local.head<2>());
    EXPECT_NEAR(
        (frame.to_world(frame.to_local(sheet.mesh.positions[k])) - sheet.mesh.positions[k]).norm(),
        0, 1e-12);
  }
}

}  // namespace
}  // namespace rangefill
