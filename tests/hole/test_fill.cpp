#include "rangefill/hole/fill.h"

#include <gtest/gtest.h>

#include "rangefill/core/topology.h"
#include "rangefill/hole/holes.h"
#include "support.h"

namespace rangefill {
namespace {

// Two triangles (a, b, c), (a, c, d) of a slightly bent quadrilateral: its one loop is its border,
// and the chord a–c is a mesh edge.
struct Quad {
  Mesh mesh;
  MeshTopology topology;
  BoundaryLoop loop;
  int chord_start = 0;  // position k in the loop such that (k, k + 2) is the mesh edge a–c
};

Quad bent_quad() {
  Quad quad;
  quad.mesh = make_mesh({{0, 0, 0}, {1, 0, 0.2}, {1, 1, 0}, {0, 1, 0.2}}, {{0, 1, 2}, {0, 2, 3}});
  quad.topology = build_topology(quad.mesh);
  const HoleSet holes = find_holes(quad.mesh, quad.topology);
  quad.loop = holes.loops.at(0);
  const std::vector<int>& v = quad.loop.vertices;
  quad.chord_start = find_halfedge(quad.mesh, quad.topology, v[0], v[2]) >= 0 ||
                             find_halfedge(quad.mesh, quad.topology, v[2], v[0]) >= 0
                         ? 0
                         : 1;
  return quad;
}

Fill fill_of(const Quad& quad, std::vector<Triangle> triangles) {
  Fill fill;
  fill.boundary = quad.loop.vertices;
  fill.triangles = std::move(triangles);
  return fill;
}

// The quad's loop closed by the chord k–(k+2): triangles (k+2, k+1, k) and (k, k+3, k+2).
std::vector<Triangle> closing(int k) {
  return {{(k + 2) % 4, (k + 1) % 4, k}, {k, (k + 3) % 4, (k + 2) % 4}};
}

// fill_defect accepts a fill that joins as a manifold, and names the defect of a boundary
// edge used forwards, a fill with a border of its own, an edge used twice the same way, a chord
// the mesh already has, a degenerate triangle and, given a viewer, a triangle seen from behind.
TEST(FillDefect, NamesWhatKeepsAFillFromJoiningAsAManifold) {
  const Quad quad = bent_quad();
  ASSERT_EQ(quad.loop.vertices.size(), 4u);
  const int free_chord = quad.chord_start + 1;  // b–d: not a mesh edge
  EXPECT_FALSE(fill_defect(quad.mesh, quad.topology, fill_of(quad, closing(free_chord))));

  // Wrong direction: the same triangles turned over use each boundary edge forwards.
  std::vector<Triangle> flipped = closing(free_chord);
  for (Triangle& t : flipped) std::swap(t[0], t[2]);
  EXPECT_TRUE(fill_defect(quad.mesh, quad.topology, fill_of(quad, flipped)));
  // A border of its own: one triangle leaves two boundary edges and the chord open.
  EXPECT_TRUE(fill_defect(quad.mesh, quad.topology, fill_of(quad, {closing(free_chord)[0]})));
  // An edge twice in one direction.
  std::vector<Triangle> doubled = closing(free_chord);
  doubled.push_back(doubled[0]);
  EXPECT_TRUE(fill_defect(quad.mesh, quad.topology, fill_of(quad, doubled)));
  // The chord a–c duplicates the mesh's own edge (the fill would make a closed two-sided pillow).
  EXPECT_TRUE(fill_defect(quad.mesh, quad.topology, fill_of(quad, closing(quad.chord_start))));
  // A degenerate triangle: a new point at the middle of the free chord, on the segment.
  Fill degenerate = fill_of(quad, {});
  const int k = free_chord % 4;
  const Vec3 middle = (quad.mesh.positions[quad.loop.vertices[k]] +
                       quad.mesh.positions[quad.loop.vertices[(k + 2) % 4]]) /
                      2;
  degenerate.points.push_back(middle);
  degenerate.triangles = {{(k + 2) % 4, (k + 1) % 4, 4},
                          {4, (k + 1) % 4, k},
                          {k, (k + 3) % 4, 4},
                          {4, (k + 3) % 4, (k + 2) % 4}};
  EXPECT_FALSE(fill_defect(quad.mesh, quad.topology, degenerate));
  degenerate.points[0] = quad.mesh.positions[quad.loop.vertices[(k + 1) % 4]] * 0.5 +
                         quad.mesh.positions[quad.loop.vertices[k]] * 0.5;  // on edge k–(k+1)
  EXPECT_TRUE(fill_defect(quad.mesh, quad.topology, degenerate));

  // Seen by a viewer: the fill faces −z (the quad's faces face +z), so a viewer above sees it
  // from behind; one below sees it from the front.
  const Fill good = fill_of(quad, closing(free_chord));
  const Vec3 from_above = Vec3::UnitZ(), from_below = -Vec3::UnitZ();
  EXPECT_TRUE(fill_defect(quad.mesh, quad.topology, good, &from_above));
  EXPECT_FALSE(fill_defect(quad.mesh, quad.topology, good, &from_below));
}

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
