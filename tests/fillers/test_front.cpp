// The advancing front (front.h), directly on a flat hole and through repair(): a spherical cap
// filled by the front, a hole round a thin tube that no projection plane can unfold, and the
// last pass's patch of a whole loop.
#include "rangefill/fillers/front.h"
#include "rangefill/image/stitch.h"

#include <cmath>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "rangefill/eval/metrics.h"
#include "rangefill/repair/pipeline.h"
#include "support.h"

namespace rangefill {
namespace {

// On a flat grid the front's points stay on the plane, the fill joins the hole as a manifold
// (validate_fill) and covers exactly the hole's area: no triangle folds over another.
TEST(FillByFront, FlatHoleIsCoveredExactly) {
  const Mesh sheet = testing::remove_faces(
      testing::make_grid(20), [](const Vec3& p) { return (p - Vec3(9.6, 10.3, 0)).norm() < 5.5; });
  const MeshTopology topology = build_topology(sheet);
  const BoundaryLoop hole = testing::inner_loop(sheet);
  ASSERT_GT(hole.vertices.size(), 20u);
  std::vector<Vec3> samples;
  for (const Triangle& t : sheet.triangles) {
    for (int v : t) samples.push_back(sheet.positions[v]);
  }
  const IntersectionIndex faces(sheet);
  const FillOutcome outcome =
      fill_by_front(sheet, topology, faces, hole,
                    MlsSurface(samples, std::vector<Vec3>(samples.size(), Vec3::UnitZ())));
  ASSERT_TRUE(std::holds_alternative<Fill>(outcome));
  const Fill& fill = std::get<Fill>(outcome);
  EXPECT_FALSE(fill_defect(sheet, topology, fill));
  EXPECT_EQ(fill.boundary, hole.vertices);
  ASSERT_GT(fill.points.size(), 10u);
  for (const Vec3& p : fill.points) {
    EXPECT_NEAR(p.z(), 0, 1e-9);
    EXPECT_LT((p - Vec3(9.6, 10.3, 0)).norm(), 5.5);  // inside the hole
  }
  auto position = [&](int id) -> const Vec3& {
    const int n = static_cast<int>(fill.boundary.size());
    return id < n ? sheet.positions[fill.boundary[id]] : fill.points[id - n];
  };
  double area = 0;
  for (const Triangle& t : fill.triangles) {
    const Vec3 cross = (position(t[1]) - position(t[0])).cross(position(t[2]) - position(t[0]));
    EXPECT_GT(cross.z(), 0);  // the fill faces +z, like the sheet around it
    area += 0.5 * cross.norm();
  }
  EXPECT_NEAR(area, hole.area, 1e-9 * hole.area);
}

// The one hole of `cut` filled by `method`: nothing left open, the input kept bit for bit, the
// result a closed manifold.
void expect_one_hole_closed_by(const Mesh& cut, const RepairResult& result,
                               const std::string& filler) {
  ASSERT_EQ(result.holes.size(), 1u);
  EXPECT_TRUE(result.holes[0].filled) << result.holes[0].failure;
  EXPECT_EQ(result.holes[0].filler, filler);
  EXPECT_EQ(result.open_count(OpenReason::failed), 0);
  testing::expect_input_preserved(cut, result.mesh);
  EXPECT_TRUE(check_manifold(result.mesh).closed_manifold());
}

// A cap of 40° cut from a sphere, filled by the front from the start: the result is a closed
// manifold, every new vertex lies within 0.05 d_m of the sphere (the MLS surface of the zone
// follows the sphere), and no new face intersects anything.
TEST(FrontFiller, ClosesASphereCapOnTheSphere) {
  const Mesh sphere = testing::make_sphere(24);
  const Mesh cut = testing::remove_faces(
      sphere, [](const Vec3& p) { return p.z() > std::cos(40 * M_PI / 180); });
  const double mean_edge = mean_edge_length(cut);
  RepairOptions options;
  options.chain = make_filler_chain("front", "least-area");
  options.selection.candidates.clear();  // the chain alone
  const RepairResult result = repair(cut, options);
  expect_one_hole_closed_by(cut, result, "front");
  ASSERT_GT(result.mesh.vertex_count(), cut.vertex_count() + 100);
  for (int v = cut.vertex_count(); v < result.mesh.vertex_count(); ++v) {
    EXPECT_LT(std::abs(result.mesh.positions[v].norm() - 1), 0.05 * mean_edge) << "vertex " << v;
    EXPECT_GT(result.mesh.positions[v].z(), std::cos(40 * M_PI / 180) - mean_edge);
  }
  const std::vector<int> generated = faces_of_hole(result.mesh, kAnyHole);
  EXPECT_EQ(count_self_intersections(result.mesh, generated), 0);
  const double edge_ratio = mean_edge_length(result.mesh, generated) / mean_edge;
  EXPECT_GT(edge_ratio, 0.7);
  EXPECT_LT(edge_ratio, 1.5);
}

// A closed tube of radius r along z from −length/2 to length/2: `around` × `along` quads, each
// end closed by a fan round a centre vertex; outward-facing.
Mesh capped_tube(double r, double length, int around, int along) {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  for (int j = 0; j <= along; ++j) {
    for (int i = 0; i < around; ++i) {
      const double angle = 2 * M_PI * i / around;
      positions.emplace_back(r * std::cos(angle), r * std::sin(angle),
                             length * (static_cast<double>(j) / along - 0.5));
    }
  }
  auto id = [&](int i, int j) { return j * around + i % around; };
  for (int j = 0; j < along; ++j) {
    for (int i = 0; i < around; ++i) {
      triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  const int bottom = static_cast<int>(positions.size());
  positions.emplace_back(0, 0, -length / 2);
  positions.emplace_back(0, 0, length / 2);
  for (int i = 0; i < around; ++i) {
    triangles.push_back({bottom, id(i + 1, 0), id(i, 0)});
    triangles.push_back({bottom + 1, id(i, along), id(i + 1, along)});
  }
  return make_mesh(positions, triangles);
}

// A band cut three quarters of the way round a thin tube (|z| < 0.15 and x > −0.15 on a tube of
// radius 0.2) leaves one loop that no plane sees from the front with a simple boundary (a complex
// hole: the planes alone fill it only in parts, Section VI-C). With the default fallbacks it is
// closed by the front, not on a plane, into a closed manifold without self-intersections whose new
// vertices lie within 0.25 d_m of the tube (the tube's facets themselves sag 0.03 d_m from the
// cylinder).
TEST(FrontFiller, ClosesAHoleWrappedRoundATube) {
  const Mesh tube = capped_tube(0.2, 2, 24, 40);
  ASSERT_TRUE(check_manifold(tube).closed_manifold());
  const Mesh cut = testing::remove_faces(
      tube, [](const Vec3& p) { return std::abs(p.z()) < 0.15 && p.x() > -0.15; });
  const HoleSet holes = find_holes(cut, build_topology(cut));
  ASSERT_EQ(holes.loops.size(), 1u);
  const double mean_edge = mean_edge_length(cut);

  RepairOptions planes_only;
  planes_only.chain = make_filler_chain("plane", "none");
  planes_only.selection.candidates.clear();  // the chain alone
  const RepairResult parts = repair(cut, planes_only);
  ASSERT_FALSE(parts.holes.empty());
  EXPECT_EQ(parts.holes[0].filler, "plane-in-part");

  const RepairResult result = repair(cut, testing::paper_chain());
  ASSERT_FALSE(result.holes.empty());
  for (const HoleReport& report : result.holes) {
    EXPECT_TRUE(report.filled) << report.failure;
    EXPECT_NE(report.filler, "plane");
  }
  EXPECT_EQ(result.holes[0].filler, "front");
  EXPECT_EQ(result.open_count(OpenReason::failed), 0);
  testing::expect_input_preserved(cut, result.mesh);
  EXPECT_TRUE(check_manifold(result.mesh).closed_manifold());
  const std::vector<int> generated = faces_of_hole(result.mesh, kAnyHole);
  ASSERT_FALSE(generated.empty());
  EXPECT_EQ(count_self_intersections(result.mesh, generated), 0);
  for (int v = cut.vertex_count(); v < result.mesh.vertex_count(); ++v) {
    const Vec3& p = result.mesh.positions[v];
    EXPECT_LT(std::abs(p.head<2>().norm() - 0.2), 0.25 * mean_edge) << "vertex " << v;
    EXPECT_LT(std::abs(p.z()), 0.15 + mean_edge);
  }
}

// In the last pass a part's rest would stay open, so the whole loop's patch (Liepa's) comes
// before the part: with one pass and no front, the tube's band is closed all the same, where the
// part alone leaves a loop open.
TEST(FrontFiller, LastPassPatchesTheWholeLoopRatherThanAPart) {
  const Mesh cut = testing::remove_faces(capped_tube(0.2, 2, 24, 40), [](const Vec3& p) {
    return std::abs(p.z()) < 0.15 && p.x() > -0.15;
  });
  RepairOptions one_pass;
  one_pass.passes = 1;
  one_pass.chain = make_filler_chain("plane", "none");
  one_pass.selection.candidates.clear();  // the chain alone
  const RepairResult part = repair(cut, one_pass);
  ASSERT_EQ(part.holes.size(), 1u);
  EXPECT_EQ(part.holes[0].filler, "plane-in-part");
  EXPECT_EQ(part.open_count(OpenReason::failed), 1);

  one_pass.chain = make_filler_chain("plane", "least-area");
  const RepairResult whole = repair(cut, one_pass);
  expect_one_hole_closed_by(cut, whole, "liepa");
  EXPECT_EQ(count_self_intersections(whole.mesh, faces_of_hole(whole.mesh, kAnyHole)), 0);
}

}  // namespace
}  // namespace rangefill
