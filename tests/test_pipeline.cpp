// End-to-end repairs of built surfaces with a known answer.
#include "rangefill/pipeline.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <set>

#include <gtest/gtest.h>

#include "rangefill/errors.h"
#include "rangefill/metrics.h"
#include "support.h"

namespace rangefill {
namespace {

// The ids of the loops that are not the longest of their component (the holes of an open sheet).
std::vector<int> inner_loops(const Mesh& mesh) {
  std::vector<int> ids;
  for (const BoundaryLoop& loop : find_holes(mesh, build_topology(mesh)).loops) {
    if (!loop.longest_in_component) ids.push_back(loop.id);
  }
  return ids;
}

std::vector<Vec3> generated_vertices(const Mesh& mesh) {
  std::vector<Vec3> points;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (mesh.vertex_hole[v] != kOriginal) points.push_back(mesh.positions[v]);
  }
  return points;
}

class EveryBackend : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryBackend, TiltedPlaneComesBackOnThePlane) {
  // A 40×40 grid, rotated and moved, with a disk of radius 8 removed from its middle.
  const testing::TiltedSheet sheet = testing::make_tilted_sheet(
      40, Eigen::AngleAxisd(0.9, Vec3(1, -2, 0.5).normalized()).toRotationMatrix(), Vec3(3, -7, 11),
      Vec3(20, 20, 0), 8);
  RepairOptions options;
  options.inpainter = GetParam();
  options.holes = {sheet.hole.id};
  const RepairResult result = repair(sheet.mesh, options);
  ASSERT_EQ(result.holes.size(), 1u);
  ASSERT_TRUE(result.holes[0].filled) << result.holes[0].failure;
  EXPECT_EQ(result.holes[0].method, "plane");
  EXPECT_EQ(result.holes_left, 0);
  testing::expect_input_preserved(sheet.mesh, result.mesh);

  const std::vector<Vec3> points = generated_vertices(result.mesh);
  ASSERT_GT(points.size(), 100u);
  for (const Vec3& p : points) EXPECT_LT(sheet.distance(p), 1e-6 * sheet.size);
  const ManifoldCheck check = check_manifold(result.mesh);
  EXPECT_EQ(check.boundary_loops, 1);  // the sheet's own border
  EXPECT_EQ(check.nonmanifold_edges + check.misoriented_edges + check.nonmanifold_vertices, 0);
}

INSTANTIATE_TEST_SUITE_P(Pipeline, EveryBackend, ::testing::ValuesIn(inpainter_names()));

TEST(Pipeline, HarmonicSaddleComesBackWithNavierStokes) {
  // z = (x² − y²)/2 over [−1, 1]², spacing 0.05, a disk of radius 0.4 removed.
  const int n = 40;
  Mesh grid = testing::make_grid(n);
  for (Vec3& p : grid.positions) {
    p = Vec3(p.x() * 2.0 / n - 1, p.y() * 2.0 / n - 1, 0);
    p.z() = (p.x() * p.x() - p.y() * p.y()) / 2;
  }
  const Mesh saddle =
      testing::remove_faces(grid, [](const Vec3& p) { return p.head<2>().norm() < 0.4; });
  const double d_m = mean_edge_length(saddle);
  // With the quadric trend the back-end only restores a residual of zero. Without it, OpenCV's NS
  // (a fast-marching transport, not a Laplace solve) is off by 0.74-0.83 d_m on the bare image of
  // this saddle for radii 5-10; a flat fill would be off by up to 1.6 d_m.
  for (const auto& [trend, bound] : {std::pair{TrendKind::quadric, 0.1}, {TrendKind::none, 0.75}}) {
    RepairOptions options;
    options.inpainter = "ns";
    options.trend = trend;
    options.holes = inner_loops(saddle);
    const RepairResult result = repair(saddle, options);
    ASSERT_TRUE(result.holes.at(0).filled) << result.holes[0].failure;
    EXPECT_EQ(result.holes[0].method, "plane");
    double worst = 0;
    for (const Vec3& p : generated_vertices(result.mesh)) {
      worst = std::max(worst, std::abs(p.z() - (p.x() * p.x() - p.y() * p.y()) / 2));
    }
    std::printf("saddle, ns, trend %s: max |z - (x^2 - y^2)/2| = %.4f d_m\n",
                trend_name(trend).c_str(), worst / d_m);
    EXPECT_LT(worst, bound * d_m) << trend_name(trend);
  }
}

struct CapCase {
  std::string backend;
  double half_angle_degrees;
  double max_above_sphere;  // in d_m
};

void PrintTo(const CapCase& c, std::ostream* os) {
  *os << c.backend << " " << c.half_angle_degrees << "deg";
}

class SphereCap : public ::testing::TestWithParam<CapCase> {};

// The generated vertices never sink below the cutting plane (a flat fill is the worst acceptable)
// and stay within 0.1 d_m of the sphere. The automatic trend takes the sphere here; the quadric
// alone overshoots the wide cap: a height field continued with the curvature of the rim rises
// above a sphere, whose height field curves faster towards its rim (1.05–1.08 d_m on 40°).
TEST_P(SphereCap, FillStaysBetweenCuttingPlaneAndSphere) {
  const Mesh sphere = testing::make_sphere(24);
  const double d_m = mean_edge_length(sphere);
  ASSERT_NEAR(d_m, 0.05, 0.01);
  const double cut = std::cos(GetParam().half_angle_degrees * M_PI / 180);
  const Mesh capless = testing::remove_faces(sphere, [&](const Vec3& p) { return p.z() > cut; });
  RepairOptions options;
  options.inpainter = GetParam().backend;
  const RepairResult result = repair(capless, options);
  ASSERT_EQ(result.holes.size(), 1u);
  ASSERT_TRUE(result.holes[0].filled) << result.holes[0].failure;
  EXPECT_EQ(result.holes[0].method, "plane");  // the numbers are the back-end's
  EXPECT_EQ(result.holes[0].trend, TrendKind::sphere);
  testing::expect_input_preserved(capless, result.mesh);
  EXPECT_TRUE(check_manifold(result.mesh).closed_manifold());
  EXPECT_EQ(count_self_intersections(result.mesh, faces_of_hole(result.mesh, kAnyHole)), 0);

  // The boundary is jagged: the plane is taken through its lowest vertex.
  double plane = 1;
  const HoleSet holes = find_holes(capless, build_topology(capless));
  for (int v : holes.loops.at(0).vertices) plane = std::min(plane, capless.positions[v].z());
  double below_sphere = 0, above_sphere = 0, lowest = 1;
  for (const Vec3& p : generated_vertices(result.mesh)) {
    lowest = std::min(lowest, p.z());
    below_sphere = std::max(below_sphere, 1 - p.norm());
    above_sphere = std::max(above_sphere, p.norm() - 1);
  }
  EXPECT_GT(lowest, plane - 0.1 * d_m);
  EXPECT_LT(above_sphere, GetParam().max_above_sphere * d_m);
  std::printf(
      "cap %g deg, %s: generated vertices from %.3f d_m below to %.3f d_m above the sphere; "
      "a flat fill reaches %.3f d_m below\n",
      GetParam().half_angle_degrees, GetParam().backend.c_str(), below_sphere / d_m,
      above_sphere / d_m, (1 - plane) / d_m);
}

std::vector<CapCase> cap_cases() {
  std::vector<CapCase> cases;
  for (const std::string& backend : inpainter_names()) {
    cases.push_back({backend, 20, 0.1});
    cases.push_back({backend, 40, 0.1});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Pipeline, SphereCap, ::testing::ValuesIn(cap_cases()),
                         [](const auto& info) {
                           return info.param.backend + "_" +
                                  std::to_string(static_cast<int>(info.param.half_angle_degrees));
                         });

TEST(Pipeline, PaperPipelineWithoutTrendSagsBelowTheCutOnACap) {
  // Why the trend is on by default: OpenCV's back-ends alone fill a 40° cap below its cutting
  // plane, worse than a flat fill.
  const Mesh capless = testing::remove_faces(
      testing::make_sphere(24), [](const Vec3& p) { return p.z() > std::cos(40 * M_PI / 180); });
  const HoleSet holes = find_holes(capless, build_topology(capless));
  double plane = 1;
  for (int v : holes.loops.at(0).vertices) plane = std::min(plane, capless.positions[v].z());
  for (const char* backend : {"ns", "telea"}) {
    RepairOptions options;
    options.inpainter = backend;
    options.trend = TrendKind::none;
    const RepairResult result = repair(capless, options);
    ASSERT_TRUE(result.holes.at(0).filled) << backend;
    double lowest = 1;
    for (const Vec3& p : generated_vertices(result.mesh)) lowest = std::min(lowest, p.z());
    EXPECT_LT(lowest, plane) << backend;
  }
}

// Wang & Oliveira's MLS height fit, with the default (automatic) trend, restores a sphere's 20° and
// 40° caps within 0.1 d_m. The sphere trend does the work on the 40° cap: on the quadric's residual
// the quadratics continued from the rim rise above the sphere, whose height field curves faster
// towards the rim than at the top (their "egg-like shape"), by 1.0 d_m at the default α and ring.
TEST(Pipeline, MlsBringsSphereCapsBack) {
  const Mesh sphere = testing::make_sphere(24);
  const double d_m = mean_edge_length(sphere);
  for (const auto& [degrees, bound] : {std::pair{20.0, 0.1}, {40.0, 0.1}}) {
    const double cut = std::cos(degrees * M_PI / 180);
    const Mesh capless = testing::remove_faces(sphere, [&](const Vec3& p) { return p.z() > cut; });
    RepairOptions options;
    options.inpainter = "mls";
    const RepairResult result = repair(capless, options);
    ASSERT_TRUE(result.holes.at(0).filled) << result.holes[0].failure;
    EXPECT_EQ(result.holes[0].method, "plane");
    double worst = 0;
    for (const Vec3& p : generated_vertices(result.mesh))
      worst = std::max(worst, std::abs(p.norm() - 1));
    std::printf("cap %g deg, mls: generated vertices within %.3f d_m of the sphere\n", degrees,
                worst / d_m);
    EXPECT_LT(worst, bound * d_m) << degrees << " deg";
  }
}

// Colour in, colour out: a sheet coloured by a linear gradient gets the gradient continued across
// its filled hole (the channels are inpainted like depth, Wang & Oliveira 4.4), and by the
// advancing front something between the boundary's colours; the input's colours stay bit for bit.
TEST(Pipeline, ColourGradientIsContinuedAcrossTheHole) {
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  testing::TiltedSheet sheet =
      testing::make_tilted_sheet(40, rotation, Vec3(1, 2, 3), Vec3(20, 20, 0), 8);
  auto gradient = [&](const Vec3& world) {
    const Vec3 grid = rotation.transpose() * (world - sheet.shift);
    return Rgb(0.1 + 0.02 * grid.x(), 0.9 - 0.015 * grid.y(), 0.3 + 0.005 * (grid.x() + grid.y()));
  };
  for (const Vec3& p : sheet.mesh.positions) sheet.mesh.colors.push_back(gradient(p));
  struct Case {
    std::string inpainter;
    TrendKind trend;
    Filler filler;
    double bound;
  };
  for (const Case& c : {Case{"ns", TrendKind::quadric, Filler::plane, 1e-4},
                        Case{"mls", TrendKind::none, Filler::plane, 1e-4},
                        Case{"ns", TrendKind::quadric, Filler::front, 0.03}}) {
    SCOPED_TRACE(c.inpainter + " " + trend_name(c.trend) +
                 (c.filler == Filler::front ? " front" : ""));
    RepairOptions options;
    options.inpainter = c.inpainter;
    options.trend = c.trend;
    options.filler = c.filler;
    options.holes = {sheet.hole.id};
    const RepairResult result = repair(sheet.mesh, options);
    ASSERT_TRUE(result.holes.at(0).filled) << result.holes[0].failure;
    testing::expect_input_preserved(sheet.mesh, result.mesh);
    ASSERT_EQ(result.mesh.colors.size(), result.mesh.positions.size());
    EXPECT_EQ(std::memcmp(result.mesh.colors.data(), sheet.mesh.colors.data(),
                          sizeof(Rgb) * sheet.mesh.colors.size()),
              0);
    double worst = 0;
    int generated = 0;
    for (int v = sheet.mesh.vertex_count(); v < result.mesh.vertex_count(); ++v, ++generated) {
      worst = std::max(
          worst,
          double(
              (result.mesh.colors[v] - gradient(result.mesh.positions[v])).cwiseAbs().maxCoeff()));
    }
    ASSERT_GT(generated, 100);
    std::printf("colour gradient: largest channel error at generated vertices %.2g\n", worst);
    EXPECT_LT(worst, c.bound);
  }
}

TEST(Pipeline, ResultDoesNotDependOnThreadCount) {
  Mesh sphere = testing::make_sphere(16);
  Mesh holed = testing::remove_faces(
      sphere, [](const Vec3& p) { return p.z() > 0.9 || p.x() > 0.92 || p.y() < -0.93; });
  RepairOptions options;
  const RepairResult one = repair(holed, options);
  options.threads = 3;
  const RepairResult three = repair(holed, options);
  ASSERT_EQ(one.holes.size(), 3u);
  EXPECT_EQ(one.mesh.triangles, three.mesh.triangles);
  ASSERT_EQ(one.mesh.positions.size(), three.mesh.positions.size());
  EXPECT_EQ(std::memcmp(one.mesh.positions.data(), three.mesh.positions.data(),
                        sizeof(Vec3) * one.mesh.positions.size()),
            0);
  EXPECT_EQ(one.restoration_matrix, three.restoration_matrix);
}

// ------------------------------------------------------------------------------------------------
// Hard holes: closed surfaces built with a known answer, faces removed, repaired, and measured
// against the surface they were cut from. Each is repaired twice: with the default fallbacks
// (the advancing front takes what no plane sees whole) and by the paper's pipeline alone (planes,
// then the hole in parts on planes of their own, Section VI-C).

struct HardOutcome {
  RepairResult result;
  double worst = 0;      // largest distance of a generated face sample to the true surface, d_m
  double hausdorff = 0;  // symmetric, generated faces against the removed ones, d_m
};

HardOutcome repair_hard_case(const Mesh& truth, const Mesh& holed, const RepairOptions& options,
                             const std::string& name) {
  HardOutcome outcome;
  outcome.result = repair(holed, options);
  const Mesh& mesh = outcome.result.mesh;
  testing::expect_input_preserved(holed, mesh);
  EXPECT_TRUE(check_manifold(mesh).closed_manifold());
  EXPECT_EQ(outcome.result.holes_left, 0);
  const std::vector<int> generated = faces_of_hole(mesh, kAnyHole);
  EXPECT_EQ(count_self_intersections(mesh, generated), 0);
  std::string methods;
  for (const HoleReport& hole : outcome.result.holes) {
    EXPECT_TRUE(hole.filled) << hole.failure;
    methods += (methods.empty() ? "" : ", ") + hole.method;
  }
  if (generated.empty()) {
    ADD_FAILURE() << name << ": nothing generated";
    return outcome;
  }
  const double d_m = mean_edge_length(holed);
  std::vector<int> all(truth.face_count()), removed;
  std::iota(all.begin(), all.end(), 0);
  const std::set<Triangle> kept(holed.triangles.begin(), holed.triangles.end());
  std::copy_if(all.begin(), all.end(), std::back_inserter(removed),
               [&](int f) { return !kept.count(truth.triangles[f]); });
  outcome.worst = surface_distance(mesh, generated, truth, all, d_m / 4).from_first / d_m;
  outcome.hausdorff = surface_distance(mesh, generated, truth, removed, d_m / 4).hausdorff / d_m;
  double seconds = 0;
  for (const HoleReport& hole : outcome.result.holes) seconds += hole.seconds;
  std::printf(
      "%s: %s; generated faces within %.3f d_m of the surface, H %.3f d_m, mean edge %.2f d_m, "
      "%.3f s\n",
      name.c_str(), methods.c_str(), outcome.worst, outcome.hausdorff,
      mean_edge_length(mesh, generated) / d_m, seconds);
  return outcome;
}

// The paper's pipeline alone: what is not filled on planes is not filled.
RepairOptions planes_only() {
  RepairOptions options;
  options.fallback_front = false;
  options.fallback_least_area = false;
  return options;
}

// Repairs a hole that no plane sees whole both ways: the front closes it in one go, the planes in
// parts (Section VI-C); each fill within its bound (in d_m) of the true surface.
void expect_closed_by_front_and_in_parts(const Mesh& truth, const Mesh& holed,
                                         const std::string& name, double front_bound,
                                         double parts_bound) {
  ASSERT_EQ(find_holes(holed, build_topology(holed)).loops.size(), 1u);
  const HardOutcome front = repair_hard_case(truth, holed, {}, name + ", default");
  EXPECT_EQ(front.result.holes.at(0).method, "front");
  EXPECT_LT(front.worst, front_bound);
  const HardOutcome parts = repair_hard_case(truth, holed, planes_only(), name + ", planes");
  EXPECT_TRUE(std::any_of(parts.result.holes.begin(), parts.result.holes.end(),
                          [](const HoleReport& hole) { return hole.method == "plane, in part"; }));
  EXPECT_LT(parts.worst, parts_bound);
  EXPECT_LT(parts.hausdorff, parts_bound);
}

// A band cut 300° round the middle of a capsule (radius 1, edges 0.1): no plane sees the hole
// whole. The planes fill it in parts, cut across the band (0.67 d_m from the capsule measured);
// the front in one go (0.02 d_m).
TEST(HardHoles, BandRoundACapsule) {
  const Mesh capsule = testing::make_capsule(1, 2, 0.1);
  const Mesh holed = testing::remove_faces(capsule, [](const Vec3& p) {
    return std::abs(p.z()) < 0.4 && testing::azimuth_degrees(p) <= 300;
  });
  expect_closed_by_front_and_in_parts(capsule, holed, "capsule band", 0.1, 1.0);
}

// Holes over a sharp edge and a corner of a cube (20×20 grid a side, disks of radius 0.25 about
// the middle of an edge and about a corner): planes see them whole. A smooth fill rounds the edge
// off; a flat one would cut it 3.1 d_m (edge) and 2.6 d_m (corner) deep. The fills keep more than
// half of that (0.90 and 1.13 d_m from the cube measured).
TEST(HardHoles, HoleOverASharpEdgeOrCorner) {
  const Mesh box = testing::make_box(20);
  const double d_m = mean_edge_length(box), radius = 0.25;
  for (const auto& [name, centre, flat_cut] :
       {std::tuple{"edge", Vec3(0.5, 1, 1), radius / std::sqrt(2.0)},
        std::tuple{"corner", Vec3(1, 1, 1), radius / std::sqrt(3.0)}}) {
    SCOPED_TRACE(name);
    const Vec3 around = centre;  // a lambda may not capture a structured binding in C++17
    const Mesh holed =
        testing::remove_faces(box, [&](const Vec3& p) { return (p - around).norm() < radius; });
    const HardOutcome outcome = repair_hard_case(box, holed, {}, std::string("cube ") + name);
    EXPECT_LT(outcome.worst, 0.5 * flat_cut / d_m);
  }
}

// A long thin hole along the circular crease of a spinning top (cones of rim 0.6 and height 1,
// whose normals turn 62° across the crease): 270° of the crease, 2.5 d_m wide. The planes fill it
// in parts cut across it (0.57 d_m from the surface measured), the front in one go (0.42 d_m).
TEST(HardHoles, LongThinHoleAlongACurvedCrease) {
  const Mesh top = testing::make_double_cone(0.6, 1, 20, 40);
  const Mesh holed = testing::remove_faces(top, [](const Vec3& p) {
    return std::abs(p.z()) < 0.06 && testing::azimuth_degrees(p) <= 270;
  });
  expect_closed_by_front_and_in_parts(top, holed, "crease", 1.0, 1.0);
}

// Figure 7: a zone that reaches another hole. Two disks of radius 6, 2 apart, cut from a sheet:
// each hole's zone takes in the other's rim, yet each fill stays within its own disk (the other
// hole is a gap of its image, not part of its mask) and both are filled, on the plane.
TEST(HardHoles, ZoneReachingAnotherHoleDoesNotBridgeIt) {
  const std::array<Vec3, 2> centres = {Vec3(13, 20, 0), Vec3(27, 20, 0)};
  const Mesh holed = testing::remove_faces(testing::make_grid(40), [&](const Vec3& p) {
    return (p - centres[0]).norm() < 6 || (p - centres[1]).norm() < 6;
  });
  RepairOptions options;
  options.holes = inner_loops(holed);
  ASSERT_EQ(options.holes.size(), 2u);
  const RepairResult result = repair(holed, options);
  ASSERT_EQ(result.holes.size(), 2u);
  for (const HoleReport& hole : result.holes) {
    EXPECT_TRUE(hole.filled) << hole.failure;
    EXPECT_EQ(hole.method, "plane");
    EXPECT_EQ(hole.other_holes.size(), 1u) << "the zone reaches the other hole";
  }
  EXPECT_EQ(result.holes_left, 0);
  testing::expect_input_preserved(holed, result.mesh);
  for (int v = holed.vertex_count(); v < result.mesh.vertex_count(); ++v) {
    const Vec3& p = result.mesh.positions[v];
    EXPECT_EQ(p.z(), 0);
    const Vec3& own = centres[p.x() < 20 ? 0 : 1];
    EXPECT_EQ(result.holes[p.x() < 20 ? 0 : 1].id, result.mesh.vertex_hole[v]);
    EXPECT_LT((p - own).norm(), 6.0) << "vertex " << v << " outside its own hole";
  }
  EXPECT_EQ(check_manifold(result.mesh).boundary_loops, 1);  // the sheet's border
}

// Figure 7e–f: a zone that encloses an island it does not grow onto. A block 10 high stands 1
// from a hole of radius 8; with γ = 40° the normal diffusion (eq. 4) refuses its walls, so the zone
// grows round it (12 rings) and the block is a gap in the range image, interpolated (Section VI-B)
// and not filled: the fill lies on the sheet, within the hole.
TEST(HardHoles, ZoneEnclosingAnIslandDoesNotCoverIt) {
  const Vec3 centre(14, 20, 0);
  Mesh sheet = testing::make_grid(40);
  auto on_block = [](const Vec3& p) {
    return std::abs(p.x() - 25) <= 2 && std::abs(p.y() - 20) <= 2;
  };
  for (Vec3& p : sheet.positions) {
    if (on_block(p)) p.z() = 10;
  }
  const Mesh holed =
      testing::remove_faces(sheet, [&](const Vec3& p) { return (p - centre).norm() < 8; });
  RepairOptions options;
  options.zone.gamma_degrees = 40;
  options.zone.rings = 12;
  options.holes = inner_loops(holed);
  ASSERT_EQ(options.holes.size(), 1u);

  const SurfaceContext surface(holed, 0);
  const Zone zone =
      grow_zone(holed, surface.topology, surface.holes, surface.holes.loops.at(options.holes[0]),
                surface.normals, surface.mean_edge, options.zone);
  bool beyond_block = false;
  for (int f : zone.faces) {
    for (int v : holed.triangles[f]) {
      EXPECT_FALSE(on_block(holed.positions[v]) && holed.positions[v].z() > 0) << "face " << f;
      beyond_block = beyond_block || holed.positions[v].x() > 28;
    }
  }
  EXPECT_TRUE(beyond_block) << "the zone does not reach round the block";

  const RepairResult result = repair(holed, options);
  ASSERT_EQ(result.holes.size(), 1u);
  ASSERT_TRUE(result.holes[0].filled) << result.holes[0].failure;
  EXPECT_EQ(result.holes[0].method, "plane");
  EXPECT_GT(result.holes[0].gap_pixels, 0);
  testing::expect_input_preserved(holed, result.mesh);
  for (const Vec3& p : generated_vertices(result.mesh)) {
    EXPECT_LT(std::abs(p.z()), 1e-9);
    EXPECT_LT((p - centre).norm(), 8.0);
  }
}

// An island: a disk of surface left in the middle of a hole, a component of its own. Every fill
// of the hole's outer loop would cover it, and is refused as intersecting it; the hole is reported
// with the reasons and left open, the island untouched, while another hole of the sheet is
// repaired.
TEST(HardHoles, HoleAroundAnIslandIsReportedAndTheOthersRepaired) {
  const Vec3 centre(20, 20, 0), other(33, 33, 0);
  const Mesh holed = testing::remove_faces(testing::make_grid(40), [&](const Vec3& p) {
    const double r = (p - centre).norm();
    return (r > 3 && r < 10) || (p - other).norm() < 3;
  });
  RepairOptions options;
  options.skip_longest_loops = true;  // the sheet's border and the island's own loop
  const RepairResult result = repair(holed, options);
  EXPECT_EQ(result.skipped_borders.size(), 2u);
  ASSERT_EQ(result.holes.size(), 2u);
  int filled = 0;
  for (const HoleReport& hole : result.holes) {
    if (hole.filled) {
      ++filled;
      continue;
    }
    EXPECT_EQ(hole.boundary_vertices, 64) << "not the hole round the island";
    EXPECT_NE(hole.failure.find("hole " + std::to_string(hole.id) + ": "), std::string::npos);
    EXPECT_NE(hole.failure.find("intersect"), std::string::npos) << hole.failure;
    EXPECT_EQ(hole.failure.find('\n'), std::string::npos);
  }
  EXPECT_EQ(filled, 1);
  EXPECT_EQ(result.holes_left, 1);
  testing::expect_input_preserved(holed, result.mesh);
  for (const Vec3& p : generated_vertices(result.mesh)) EXPECT_LT((p - other).norm(), 3.0);
}

// ------------------------------------------------------------------------------------------------
// Open surfaces: which loops are filled.

// Two open sheets side by side, two components: a 30×30 grid with a small hole (radius 3, at
// x = 8) and a large one (radius 6, at x = 20), and a 10×10 grid 40 to the right with a hole of
// radius 2.
Mesh two_open_sheets() {
  Mesh sheet = testing::remove_faces(testing::make_grid(30), [](const Vec3& p) {
    return (p - Vec3(8, 15, 0)).norm() < 3 || (p - Vec3(20, 15, 0)).norm() < 6;
  });
  const Mesh small = testing::remove_faces(
      testing::make_grid(10), [](const Vec3& p) { return (p - Vec3(5, 5, 0)).norm() < 2; });
  const int offset = sheet.vertex_count();
  for (const Vec3& p : small.positions) sheet.positions.push_back(p + Vec3(40, 0, 0));
  for (const Triangle& t : small.triangles) {
    sheet.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  return make_mesh(sheet.positions, sheet.triangles);
}

// The loop whose vertices lie round `centre` (x, y), nearest first.
int loop_around(const HoleSet& holes, const Mesh& mesh, const Vec3& centre) {
  int best = -1;
  double nearest = std::numeric_limits<double>::infinity();
  for (const BoundaryLoop& loop : holes.loops) {
    Vec3 mean = Vec3::Zero();
    for (int v : loop.vertices) mean += mesh.positions[v];
    mean /= static_cast<double>(loop.vertices.size());
    if ((mean - centre).norm() < nearest) {
      nearest = (mean - centre).norm();
      best = loop.id;
    }
  }
  return best;
}

TEST(OpenSurfaces, TheLongestLoopOfEachComponentIsLeftOpenAsItsBorder) {
  const Mesh sheets = two_open_sheets();
  const HoleSet holes = find_holes(sheets, build_topology(sheets));
  ASSERT_EQ(holes.loops.size(), 5u);
  std::vector<int> borders;
  for (const BoundaryLoop& loop : holes.loops) {
    if (loop.longest_in_component) borders.push_back(loop.id);
  }
  ASSERT_EQ(borders.size(), 2u);

  RepairOptions options;
  options.skip_longest_loops = true;
  const RepairResult result = repair(sheets, options);
  EXPECT_EQ(result.skipped_borders, borders);
  EXPECT_EQ(result.holes.size(), 3u);
  for (const HoleReport& hole : result.holes) {
    EXPECT_TRUE(hole.filled) << hole.failure;
    EXPECT_EQ(std::count(borders.begin(), borders.end(), hole.id), 0);
  }
  EXPECT_EQ(result.holes_left, 0);
  EXPECT_EQ(check_manifold(result.mesh).boundary_loops, 2);
  testing::expect_input_preserved(sheets, result.mesh);

  // Without the policy every loop is attempted, the borders too; but any fill of a flat sheet's
  // border would lie on the sheet itself: both are refused and reported, the holes still filled.
  const RepairResult all = repair(sheets);
  EXPECT_TRUE(all.skipped_borders.empty());
  ASSERT_EQ(all.holes.size(), 5u);
  for (const HoleReport& hole : all.holes) {
    const bool border = std::count(borders.begin(), borders.end(), hole.id) > 0;
    EXPECT_EQ(hole.filled, !border) << hole.id;
    if (border) {
      EXPECT_NE(hole.failure.find("hole " + std::to_string(hole.id)), std::string::npos);
    }
  }
  EXPECT_EQ(all.holes_left, 2);
  EXPECT_EQ(all.mesh.triangles, result.mesh.triangles);
}

TEST(OpenSurfaces, NamedLoopsAndSizeLimitsChooseWhatIsFilled) {
  const Mesh sheets = two_open_sheets();
  const HoleSet holes = find_holes(sheets, build_topology(sheets));
  const int small = loop_around(holes, sheets, Vec3(8, 15, 0));
  const int large = loop_around(holes, sheets, Vec3(20, 15, 0));
  const int other = loop_around(holes, sheets, Vec3(45, 5, 0));

  RepairOptions named;
  named.holes = {large};
  const RepairResult one = repair(sheets, named);
  ASSERT_EQ(one.holes.size(), 1u);
  EXPECT_EQ(one.holes[0].id, large);
  EXPECT_TRUE(one.holes[0].filled);
  EXPECT_EQ(check_manifold(one.mesh).boundary_loops, 4);

  // Loops larger than the limits are left open, said in `oversized`, and not counted as left.
  for (const bool by_area : {false, true}) {
    RepairOptions limited;
    limited.skip_longest_loops = true;
    if (by_area) {
      limited.max_hole_area = holes.loops[small].area * 1.01;
    } else {
      limited.max_hole_edges = static_cast<int>(holes.loops[small].vertices.size());
    }
    const RepairResult result = repair(sheets, limited);
    EXPECT_EQ(result.oversized, std::vector<int>{large}) << by_area;
    ASSERT_EQ(result.holes.size(), 2u) << by_area;  // the small hole and the other sheet's
    EXPECT_EQ(result.holes[0].id, std::min(small, other));
    EXPECT_EQ(result.holes_left, 0);
    EXPECT_EQ(check_manifold(result.mesh).boundary_loops, 3);
  }

  RepairOptions missing;
  missing.holes = {static_cast<int>(holes.loops.size())};
  EXPECT_THROW(repair(sheets, missing), InvalidInput);
}

}  // namespace
}  // namespace rangefill
