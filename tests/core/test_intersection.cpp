// Triangle intersection tests (exact predicates): pairs, the index of a mesh's faces, counts.
#include "rangefill/core/intersection.h"

#include <cmath>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

#include "support.h"

namespace rangefill {
namespace {

// Two triangles that cross: one in z = 0, one standing in x = 0 and piercing it.
Mesh crossing_pair() {
  return make_mesh({{-1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0.2, -1}, {0, 0.2, 1}, {0, 0.5, 0.2}},
                   {{0, 1, 2}, {3, 4, 5}});
}

// The crossing pair counts once, whichever of its faces are queried; a closed cube and a closed
// sphere count none (their neighbouring faces meet only where they share vertices).
TEST(CountSelfIntersections, CountsEachCrossingPairOnce) {
  const Mesh pair = crossing_pair();
  EXPECT_EQ(count_self_intersections(pair, {0, 1}), 1);
  EXPECT_EQ(count_self_intersections(pair, {0}), 1);
  EXPECT_EQ(count_self_intersections(pair, {1}), 1);
  const Mesh cube = testing::make_cube();
  std::vector<int> all(cube.face_count());
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(count_self_intersections(cube, all), 0);
  const Mesh sphere = testing::make_sphere(6);
  all.resize(sphere.face_count());
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(count_self_intersections(sphere, all), 0);
  // A sphere pushed through itself: one cap moved inwards across the other side.
  Mesh dented = sphere;
  for (Vec3& p : dented.positions) {
    if (p.z() > 0.8) p.z() -= 1.9;
  }
  EXPECT_GT(count_self_intersections(dented, all), 0);
}

// Crossing, touching at a point and overlapping in a plane intersect; triangles apart or
// degenerate (collinear corners) do not.
TEST(TrianglesIntersect, SharedPointsCount) {
  const std::array<Vec3, 3> flat = {Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_TRUE(triangles_intersect(flat, {Vec3(0, 0.2, -1), Vec3(0, 0.2, 1), Vec3(0, 0.5, 0.2)}));
  EXPECT_FALSE(triangles_intersect(flat, {Vec3(5, 0.2, -1), Vec3(5, 0.2, 1), Vec3(5, 0.5, 0.2)}));
  EXPECT_TRUE(triangles_intersect(flat, {Vec3(0, 0.3, 0), Vec3(0, 0.3, 1), Vec3(0.2, 0.3, 1)}));
  EXPECT_FALSE(triangles_intersect(flat, {Vec3(0, 0.3, 1e-9), Vec3(0, 0.3, 1), Vec3(0.2, 0.3, 1)}));
  EXPECT_TRUE(triangles_intersect(flat, {Vec3(0, 0.1, 0), Vec3(2, 0.1, 0), Vec3(0, 3, 0)}));
  EXPECT_FALSE(triangles_intersect(flat, {Vec3(-2, 0.5, 0), Vec3(0, 0.5, 0), Vec3(2, 0.5, 0)}));
}

// Two vertices at the same point (a surface touching itself, as at a cow's coincident vertices)
// are shared as one: faces meeting only there do not intersect, faces crossing beyond it do.
TEST(TrianglesIntersect, VerticesAtTheSamePointAreShared) {
  const std::array<Vec3, 3> flat = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const std::array<Vec3, 3> touching = {Vec3(0, 0, 0), Vec3(-1, 0, 1), Vec3(0, -1, 1)};
  EXPECT_FALSE(triangles_intersect(flat, touching, {0, 1, 2}, {3, 4, 5}));
  EXPECT_TRUE(triangles_intersect(flat, touching));  // unnamed corners: a point in common counts
  const std::array<Vec3, 3> crossing = {Vec3(0, 0, 0), Vec3(0.5, 0.2, 1), Vec3(0.2, 0.5, -1)};
  EXPECT_TRUE(triangles_intersect(flat, crossing, {0, 1, 2}, {3, 4, 5}));
}

// The index finds the faces a triangle meets beyond the corners it shares with them, as CGAL's
// self_intersections decides: sharing a vertex, only an opposite edge crossing counts; sharing an
// edge, only a fold onto the face; sharing all three corners, always.
TEST(IntersectionIndex, CountsWhatMeetsBeyondSharedCorners) {
  const Mesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  const IntersectionIndex index(mesh);
  const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0);
  const std::vector<int> face = {0}, none = {};
  // Sharing vertex 0: a neighbour in the fan, then one whose far edge pierces the face.
  EXPECT_EQ(index.intersecting_faces(o, Vec3(-1, 0, 0), Vec3(0, -1, 0), {0, -1, -1}), none);
  EXPECT_EQ(index.intersecting_faces(o, Vec3(0.3, 0.3, -1), Vec3(0.3, 0.3, 1), {0, -1, -1}), face);
  // Not listed as shared, a touch at a corner is a meeting.
  EXPECT_EQ(index.intersecting_faces(o, Vec3(-1, 0, 0), Vec3(0, -1, 0), {-1, -1, -1}), face);
  // Sharing edge 0-1: across it in the plane, hinged out of it, folded onto the face.
  EXPECT_EQ(index.intersecting_faces(x, o, Vec3(0.5, -1, 0), {1, 0, -1}), none);
  EXPECT_EQ(index.intersecting_faces(x, o, Vec3(0.5, 0.5, 1), {1, 0, -1}), none);
  EXPECT_EQ(index.intersecting_faces(x, o, Vec3(0.2, 0.5, 0), {1, 0, -1}), face);
  // The face itself.
  EXPECT_EQ(index.intersecting_faces(o, x, y, {0, 1, 2}), face);
  EXPECT_EQ(index.intersecting_faces(Vec3(20, 0, 0), Vec3(21, 0, 0), Vec3(20, 1, 0), {-1, -1, -1}),
            none);
  EXPECT_TRUE(IntersectionIndex(Mesh()).intersecting_faces(o, x, y, {-1, -1, -1}).empty());
}

// An index of the faces near a few regions answers every query as the index of every face does:
// triangles inside a region from the grids, those beyond every region (or crossing one's edge)
// from all the faces. Queries: triangles through the sphere's surface at random.
TEST(IntersectionIndex, RegionsChangeTheCostNotTheAnswers) {
  const Mesh sphere = testing::make_sphere(24);
  const IntersectionIndex all(sphere);
  const IntersectionIndex near(sphere, {{{Vec3(0.5, -0.3, -0.3), Vec3(1.2, 0.3, 0.3)}},
                                        {{Vec3(-0.2, -0.2, 0.8), Vec3(0.2, 0.2, 1.2)}}});
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.2, 1.2), offset(-0.3, 0.3);
  int meeting = 0;
  for (int query = 0; query < 3000; ++query) {
    const Vec3 centre(coordinate(random), coordinate(random), coordinate(random));
    const Vec3 a = centre.normalized() + Vec3(offset(random), offset(random), offset(random));
    const Vec3 b = a + Vec3(offset(random), offset(random), offset(random));
    const Vec3 c = a + Vec3(offset(random), offset(random), offset(random));
    const std::vector<int> expected = all.intersecting_faces(a, b, c, {-1, -1, -1});
    ASSERT_EQ(near.intersecting_faces(a, b, c, {-1, -1, -1}), expected) << query;
    meeting += !expected.empty();
  }
  EXPECT_GT(meeting, 1000);
}

// Faces round a shared vertex, in one plane as on a subdivided mesh: the others of a regular fan
// meet the first only where they share corners, the opposite one too (its corners lie on the
// lines of the first's edges); a face whose wedge overlaps the first's meets it, as does one whose
// far edge pierces it out of the plane. The same far from the origin, at 1e-9 of its coordinates.
TEST(TrianglesIntersect, FacesRoundASharedVertexMeetOnlyWhereTheyOverlap) {
  for (const Vec3& centre : {Vec3(0, 0, 0), Vec3(1e3, -2e3, 5e2)}) {
    const double size = centre.isZero() ? 1 : 1e-6;
    const auto at = [&](double degrees, double radius = 1, double z = 0) {
      const double angle = degrees * M_PI / 180;
      return Vec3(centre + size * Vec3(radius * std::cos(angle), radius * std::sin(angle), z));
    };
    const std::array<Vec3, 3> first = {centre, at(0), at(60)};
    for (int k = 1; k < 6; ++k) {  // vertices: the centre 0, at(60 j) j + 1
      EXPECT_FALSE(triangles_intersect(first, {centre, at(60 * k), at(60 * k + 60)}, {0, 1, 2},
                                       {0, k + 1, (k + 1) % 6 + 1}))
          << "fan face " << k << " at " << centre.transpose();
    }
    EXPECT_TRUE(triangles_intersect(first, {centre, at(30), at(120)}, {0, 1, 2}, {0, 3, 4}));
    EXPECT_TRUE(
        triangles_intersect(first, {centre, at(30, 2, -1), at(30, 2, 1)}, {0, 1, 2}, {0, 3, 4}));
    EXPECT_FALSE(
        triangles_intersect(first, {centre, at(30, 2, 0.5), at(30, 2, 1)}, {0, 1, 2}, {0, 3, 4}));
  }
}

// Two faces of a fill: one folded back onto its neighbour across their shared edge meets it.
TEST(TrianglesIntersect, AFoldAcrossASharedEdgeMeets) {
  const std::array<Vec3, 3> face = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_FALSE(triangles_intersect(face, {Vec3(1, 0, 0), Vec3(0, 0, 0), Vec3(0.5, -1, 0)},
                                   {0, 1, 2}, {1, 0, 3}));
  EXPECT_TRUE(triangles_intersect(face, {Vec3(1, 0, 0), Vec3(0, 0, 0), Vec3(0.2, 0.5, 0)},
                                  {0, 1, 2}, {1, 0, 3}));
  // The same far from the origin (coordinates rounded at 1e-10 of the edges), and a fold of the
  // size of that rounding: decided as exactly.
  const Vec3 far(1e6, -3e6, 2e6);
  const double tiny = 1e-9;
  const std::array<Vec3, 3> far_face = {far, far + Vec3(tiny, 0, 0), far + Vec3(0, tiny, 0)};
  EXPECT_FALSE(triangles_intersect(far_face,
                                   {far + Vec3(tiny, 0, 0), far, far + Vec3(tiny / 2, -tiny, 0)},
                                   {0, 1, 2}, {1, 0, 3}));
  EXPECT_TRUE(triangles_intersect(far_face,
                                  {far + Vec3(tiny, 0, 0), far, far + Vec3(tiny / 5, tiny / 2, 0)},
                                  {0, 1, 2}, {1, 0, 3}));
}

}  // namespace
}  // namespace rangefill
