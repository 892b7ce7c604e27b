// The punched-hole benchmark on the shared closed meshes, as `rangefill bench` runs it (seed 1,
// 5 holes each, the default options): a regression guard.
#include <gtest/gtest.h>

#include "rangefill/eval/evaluation.h"
#include "rangefill/io/mesh_io.h"
#include "support.h"

namespace rangefill {
namespace {

TEST(Benchmark, PunchedSharedMeshesAreRepaired) {
  RANGEFILL_REQUIRE_SHARED(data);
  int holes = 0, closed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(data / "meshes")) {
    SCOPED_TRACE(entry.path().filename().string());
    const Mesh original = read_mesh(entry.path()).mesh;
    const double d_m = mean_edge_length(original);
    PunchOptions punch;
    punch.seed = seed_for_mesh(1, entry.path().filename().string());
    const PunchResult punched = punch_holes(original, punch);
    EXPECT_EQ(punched.holes.size(), 5u);
    const RepairResult repaired = repair(punched.mesh, {});
    testing::expect_input_preserved(punched.mesh, repaired.mesh);
    EXPECT_EQ(count_self_intersections(repaired.mesh, faces_of_hole(repaired.mesh, kAnyHole)), 0);
    const ManifoldCheck check = check_manifold(repaired.mesh);
    EXPECT_EQ(check.nonmanifold_edges + check.misoriented_edges + check.nonmanifold_vertices, 0);
    for (const HoleScore& score : score_repair(original, punched, repaired, d_m)) {
      ++holes;
      if (!score.filled) {
        std::printf("%s hole %d open: %s\n", entry.path().filename().c_str(), score.hole,
                    score.failure.c_str());
        continue;
      }
      ++closed;
      EXPECT_LT(score.distance.hausdorff, 10 * d_m) << "hole " << score.hole;
    }
  }
  std::printf("%d of %d punched holes closed\n", closed, holes);
  EXPECT_EQ(holes, 60);
  // All but one close. cow 2 stays open: cow.ply
  // intersects itself there (two of the hole's boundary edges pass through faces of the other
  // sheet), so every fill on those edges meets the surface and is refused.
  EXPECT_GE(closed, 59);
}

}  // namespace
}  // namespace rangefill
