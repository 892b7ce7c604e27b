#include "rangefill/hole/holes.h"

#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "rangefill/io/mesh_io.h"
#include "support.h"

namespace rangefill {
namespace {

using testing::make_cube;
using testing::make_grid;

HoleSet holes_of(const Mesh& mesh) {
  return find_holes(mesh, build_topology(mesh));
}

// Every consecutive pair of a loop must be a half-edge of some face (the surface on its left).
void expect_loop_follows_faces(const Mesh& mesh, const BoundaryLoop& loop) {
  for (size_t k = 0; k < loop.vertices.size(); ++k) {
    const int a = loop.vertices[k], b = loop.vertices[(k + 1) % loop.vertices.size()];
    bool found = false;
    for (const Triangle& t : mesh.triangles) {
      for (int c = 0; c < 3; ++c) found |= t[c] == a && t[(c + 1) % 3] == b;
    }
    EXPECT_TRUE(found) << "loop edge " << a << "->" << b << " is not a face half-edge";
  }
}

TEST(FindHoles, ClosedCubeHasNone) {
  const HoleSet holes = holes_of(make_cube());
  EXPECT_TRUE(holes.loops.empty());
  EXPECT_TRUE(holes.pinched_vertices.empty());
}

TEST(FindHoles, CubeWithOneTriangleRemovedHasOneLoopOfThree) {
  Mesh cube = make_cube();
  cube.triangles.erase(cube.triangles.begin() + 2);  // {4, 5, 6} on z = 1
  cube.face_hole.pop_back();
  const HoleSet holes = holes_of(cube);
  ASSERT_EQ(holes.loops.size(), 1u);
  const BoundaryLoop& loop = holes.loops[0];
  EXPECT_EQ(loop.vertices.size(), 3u);
  EXPECT_NEAR(loop.perimeter, 2.0 + std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(loop.area, 0.5, 1e-12);
  EXPECT_NEAR(loop.area_share, 0.5 / 5.5, 1e-12);  // of the cube's 5.5 left
  EXPECT_FALSE(is_border(loop));
  expect_loop_follows_faces(cube, loop);
  // The filling triangle is the removed one: the loop reversed is {4, 5, 6} up to rotation.
  std::vector<int> sorted = loop.vertices;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (std::vector<int>{4, 5, 6}));
}

TEST(FindHoles, GridHasOneOuterLoop) {
  const Mesh grid = make_grid(4);
  const HoleSet holes = holes_of(grid);
  ASSERT_EQ(holes.loops.size(), 1u);
  EXPECT_EQ(holes.loops[0].vertices.size(), 16u);
  EXPECT_NEAR(holes.loops[0].perimeter, 16.0, 1e-12);
  EXPECT_NEAR(holes.loops[0].area, 16.0, 1e-12);
  EXPECT_NEAR(holes.loops[0].area_share, 1.0, 1e-12);
  EXPECT_TRUE(is_border(holes.loops[0]));
  expect_loop_follows_faces(grid, holes.loops[0]);
}

TEST(FindHoles, GridWithTwoInteriorHoles) {
  Mesh grid = make_grid(6);
  testing::remove_grid_quad(grid, 6, 4,
                            4);  // the later one first, so the earlier indices stay valid
  testing::remove_grid_quad(grid, 6, 1, 1);
  const HoleSet holes = holes_of(grid);
  ASSERT_EQ(holes.loops.size(), 3u);
  int outer = 0, interior = 0;
  for (const BoundaryLoop& loop : holes.loops) {
    expect_loop_follows_faces(grid, loop);
    if (is_border(loop)) {
      ++outer;
      EXPECT_EQ(loop.vertices.size(), 24u);
      EXPECT_NEAR(loop.area_share, 36.0 / 34.0, 1e-12);
    } else {
      ++interior;
      EXPECT_EQ(loop.vertices.size(), 4u);
      EXPECT_NEAR(loop.perimeter, 4.0, 1e-12);
      EXPECT_NEAR(loop.area, 1.0, 1e-12);
      EXPECT_NEAR(loop.area_share, 1.0 / 34.0, 1e-12);
    }
  }
  EXPECT_EQ(outer, 1);
  EXPECT_EQ(interior, 2);
}

TEST(FindHoles, NonManifoldFanIsReportedNotCrashedOn) {
  // Three triangles on the edge (0, 1).
  const Mesh fan = make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}},
                             {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  const MeshTopology topology = build_topology(fan);
  EXPECT_EQ(topology.nonmanifold_edge_count, 1);
  EXPECT_EQ(topology.nonmanifold_vertices, (std::vector<int>{0, 1}));
  const HoleSet holes = find_holes(fan, topology);
  // The six boundary edges (two per triangle) are all accounted for, closed or not.
  size_t boundary_edges = holes.open_boundary_edges;
  for (const BoundaryLoop& loop : holes.loops) boundary_edges += loop.vertices.size();
  EXPECT_EQ(boundary_edges, 6u);
}

TEST(FindHoles, BowtieGivesTwoLoopsAndAPinchedVertex) {
  const Mesh bowtie = make_mesh({{0, 0, 0}, {-1, -1, 0}, {-1, 1, 0}, {1, 1, 0}, {1, -1, 0}},
                                {{0, 2, 1}, {0, 4, 3}});
  const MeshTopology topology = build_topology(bowtie);
  EXPECT_EQ(topology.nonmanifold_vertices, (std::vector<int>{0}));
  EXPECT_EQ(face_components(bowtie, topology).count, 2);
  const HoleSet holes = find_holes(bowtie, topology);
  ASSERT_EQ(holes.loops.size(), 2u);
  EXPECT_EQ(holes.loops[0].vertices.size(), 3u);
  EXPECT_EQ(holes.loops[1].vertices.size(), 3u);
  EXPECT_EQ(holes.pinched_vertices, (std::vector<int>{0}));
}

TEST(FindHoles, HoleTouchingTheBorderAtAVertexStaysItsOwnLoop) {
  // 3x3 grid without its centre quad and its corner quad (2, 2): the hole and the outer border meet
  // at grid vertex (2, 2). Walking each fan keeps them apart instead of one figure-eight.
  Mesh grid = make_grid(3);
  testing::remove_grid_quad(grid, 3, 2, 2);  // the later one first
  testing::remove_grid_quad(grid, 3, 1, 1);
  const HoleSet holes = holes_of(grid);
  ASSERT_EQ(holes.loops.size(), 2u);
  EXPECT_EQ(holes.pinched_vertices, (std::vector<int>{10}));
  std::vector<size_t> sizes;
  for (const BoundaryLoop& loop : holes.loops) {
    sizes.push_back(loop.vertices.size());
    expect_loop_follows_faces(grid, loop);
    EXPECT_EQ(is_border(loop), loop.vertices.size() == 12u);  // shares 9/7 and 1/7
  }
  std::sort(sizes.begin(), sizes.end());
  EXPECT_EQ(sizes, (std::vector<size_t>{4, 12}));
}

// Rows of ../shared/data/stats.tsv: file -> (boundary loop lengths, d_m).
std::map<std::string, std::pair<std::vector<int>, double>> read_stats(
    const std::filesystem::path& data) {
  std::map<std::string, std::pair<std::vector<int>, double>> stats;
  std::ifstream file(data / "stats.tsv");
  std::string line;
  std::getline(file, line);  // header
  while (std::getline(file, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, '\t');) cells.push_back(cell);
    if (cells.size() < 12) continue;
    std::vector<int> loops;
    std::stringstream lengths(cells[11]);
    for (std::string length; std::getline(lengths, length, ',');)
      loops.push_back(std::stoi(length));
    stats[cells[0]] = {loops, std::stod(cells[5])};
  }
  return stats;
}

TEST(FindHoles, SharedMeshesMatchTheirPublishedLoops) {
  RANGEFILL_REQUIRE_SHARED(data);
  const auto stats = read_stats(data);
  ASSERT_GE(stats.size(), 16u);
  for (const auto& [file, expected] : stats) {
    SCOPED_TRACE(file);
    const Mesh mesh = read_mesh(data / file).mesh;
    const MeshTopology topology = build_topology(mesh);
    const HoleSet holes = find_holes(mesh, topology);
    std::vector<int> lengths;
    for (const BoundaryLoop& loop : holes.loops) {
      lengths.push_back(static_cast<int>(loop.vertices.size()));
      expect_loop_follows_faces(mesh, loop);
    }
    std::sort(lengths.rbegin(), lengths.rend());
    EXPECT_EQ(lengths, expected.first);
    EXPECT_EQ(topology.nonmanifold_edge_count, 0);
    EXPECT_TRUE(topology.nonmanifold_vertices.empty());
    EXPECT_NEAR(mean_edge_length(mesh, topology), expected.second, 1e-6 * expected.second);
  }
}

}  // namespace
}  // namespace rangefill
