#include "rangefill/fillers/fairing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "rangefill/core/errors.h"
#include "rangefill/core/intersection.h"
#include "rangefill/eval/metrics.h"
#include "rangefill/hole/patch_angles.h"
#include "rangefill/image/stitch.h"
#include "rangefill/repair/pipeline.h"
#include "support.h"

namespace rangefill {
namespace {

// The largest distance of the fill's new points from the unit sphere.
double largest_distance_from_sphere(const Fill& fill) {
  double largest = 0;
  for (const Vec3& p : fill.points) largest = std::max(largest, std::abs(p.norm() - 1));
  return largest;
}

// A cap of a sphere (about 0.6 radius wide): the faired patch lies on the sphere, its edges as
// long as those around it, no sliver; the third-order fairing (the default) follows the sphere
// more closely than CGAL's default, the second order.
TEST(FillByFairing, RestoresASphereCapAtTheDensityAround) {
  const Mesh sphere = testing::make_sphere(16);
  const Mesh capless = testing::remove_faces(sphere, [](const Vec3& p) { return p.z() > 0.95; });
  const MeshTopology topology = build_topology(capless);
  const HoleSet holes = find_holes(capless, topology);
  ASSERT_EQ(holes.loops.size(), 1u);
  const double mean_edge = mean_edge_length(capless, topology);

  FairingOptions options;
  const FillOutcome outcome =
      fill_by_fairing(capless, topology, holes.loops[0], mean_edge, options);
  ASSERT_TRUE(std::holds_alternative<Fill>(outcome)) << std::get<Refused>(outcome).detail;
  const Fill& fill = std::get<Fill>(outcome);
  ASSERT_GT(fill.points.size(), 3u);
  const double default_error = largest_distance_from_sphere(fill);
  EXPECT_LT(default_error, 0.01 * mean_edge * 16);
  EXPECT_GE(testing::smallest_angle(capless, with_larger_angles(capless, topology, fill)), 10);
  EXPECT_FALSE(fill_defect(capless, topology, fill));

  // Edge lengths: the mean new edge within 15 % of d_m.
  double total = 0;
  int count = 0;
  Mesh merged = capless;
  merge_fill(merged, fill, 0);
  for (int face : faces_of_hole(merged, 0)) {
    for (int k = 0; k < 3; ++k) {
      total += (merged.positions[merged.triangles[face][k]] -
                merged.positions[merged.triangles[face][(k + 1) % 3]])
                   .norm();
      ++count;
    }
  }
  EXPECT_NEAR(total / count / mean_edge, 1.0, 0.15);
  EXPECT_TRUE(check_manifold(merged).closed_manifold());

  options.continuity = 1;
  const FillOutcome second_order =
      fill_by_fairing(capless, topology, holes.loops[0], mean_edge, options);
  ASSERT_TRUE(std::holds_alternative<Fill>(second_order));
  EXPECT_LT(default_error, largest_distance_from_sphere(std::get<Fill>(second_order)));

  options.continuity = 3;
  EXPECT_THROW(fill_by_fairing(capless, topology, holes.loops[0], mean_edge, options),
               InvalidInput);
}

// A hole across a sharp edge of a box, by the default chain without selection: filled, the output a
// closed 2-manifold with the input's elements bit for bit, no generated face meeting another face,
// and the patch near the box (the edge is rounded, not lost).
TEST(FillByFairing, AHoleOnASharpEdgeKeepsTheIntegrityRules) {
  const int n = 24;
  const Vec3 centre(0.5, 1, 1);  // on the edge y = z = 1
  const Mesh box = testing::make_box(n);
  const Mesh holed =
      testing::remove_faces(box, [&](const Vec3& p) { return (p - centre).norm() < 0.2; });
  RepairOptions options;
  options.selection.candidates.clear();  // the chain alone: the faired patch first
  const RepairResult result = repair(holed, options);
  ASSERT_EQ(result.holes.size(), 1u);
  ASSERT_TRUE(result.holes[0].filled) << result.holes[0].failure;
  EXPECT_EQ(result.holes[0].filler, "fairing");
  testing::expect_input_preserved(holed, result.mesh);
  EXPECT_TRUE(check_manifold(result.mesh).closed_manifold());
  const std::vector<int> generated = faces_of_hole(result.mesh, kAnyHole);
  EXPECT_EQ(count_self_intersections(result.mesh, generated), 0);
  double farthest = 0;  // from the box's surface; inside it, the nearest side
  for (int v = holed.vertex_count(); v < result.mesh.vertex_count(); ++v) {
    const Vec3& p = result.mesh.positions[v];
    const Vec3 outside = (p - Vec3::Constant(1)).cwiseMax(-p).cwiseMax(0);
    const double inside = std::min({p.x(), p.y(), p.z(), 1 - p.x(), 1 - p.y(), 1 - p.z()});
    farthest = std::max(farthest, outside.norm() > 0 ? outside.norm() : inside);
  }
  EXPECT_LT(farthest, 0.2 * 0.35);  // within 35 % of the hole's radius
}

}  // namespace
}  // namespace rangefill
