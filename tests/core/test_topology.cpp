#include "rangefill/core/topology.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "support.h"

namespace rangefill {
namespace {

using testing::make_cube;
using testing::make_grid;

// The cube's 12 faces: 18 edges of two faces each, every half-edge paired with the reverse one,
// one component; find_halfedge follows the faces' orientation.
TEST(Topology, PairsTheHalfEdgesOfAClosedMesh) {
  const Mesh cube = make_cube();
  const MeshTopology topology = build_topology(cube);
  EXPECT_EQ(topology.edge_count, 18);
  EXPECT_EQ(face_components(cube, topology).count, 1);
  EXPECT_EQ(topology.nonmanifold_edge_count, 0);
  EXPECT_TRUE(topology.nonmanifold_vertices.empty());
  for (int h = 0; h < 3 * cube.face_count(); ++h) {
    const int o = topology.opposite[h];
    ASSERT_GE(o, 0) << h;
    EXPECT_EQ(topology.opposite[o], h);
    EXPECT_EQ(topology.halfedge_source(cube, o), topology.halfedge_target(cube, h));
    EXPECT_EQ(halfedges_on_edge(cube, topology, h), halfedges_on_edge(cube, topology, o));
  }
  for (int v = 0; v < cube.vertex_count(); ++v) {
    EXPECT_GE(faces_of_vertex(topology, v).size(), 3u) << v;
  }
  const int h = find_halfedge(cube, topology, 0, 2);  // face {0, 2, 1}
  ASSERT_GE(h, 0);
  EXPECT_EQ(halfedge_face(h), 0);
  EXPECT_EQ(find_halfedge(cube, topology, 0, 7), -1);
}

// Two grids side by side are two components; every face knows its own.
TEST(Topology, CountsComponents) {
  Mesh two = make_grid(2);
  const Mesh other = make_grid(2);
  const int offset = two.vertex_count();
  for (const Vec3& p : other.positions) two.positions.push_back(p + Vec3(5, 0, 0));
  for (const Triangle& t : other.triangles) {
    two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  two = make_mesh(two.positions, two.triangles);
  const FaceComponents components = face_components(two, build_topology(two));
  EXPECT_EQ(components.count, 2);
  for (int f = 0; f < two.face_count(); ++f) {
    EXPECT_EQ(components.of_face[f], f < 8 ? 0 : 1);
  }
}

// The faces around each vertex, walked round it or listed, are those that hold it, each once: on
// a closed surface, an open grid, and at a pinch (two fans), a non-manifold edge and a misoriented
// one. A walk serves every vertex of one fan through two-face edges; the others are listed.
TEST(Topology, FacesOfAVertexAreFoundByWalkingRoundIt) {
  // Edge (0, 1) has three faces, edge (1, 2) two misoriented ones, vertex 5 two fans.
  const Mesh pinched =
      make_mesh({{0, 0, 0},
                 {1, 0, 0},
                 {0, 1, 0},
                 {-1, 0, 0},
                 {0, -1, 0},
                 {0.5, 0, 1},
                 {0.5, 0, -1},
                 {1, 1, 0},
                 {0.5, 1, 2},
                 {1, 1, 2}},
                {{0, 1, 2}, {0, 3, 4}, {0, 1, 5}, {1, 0, 6}, {3, 0, 2}, {1, 2, 7}, {5, 8, 9}});
  for (const Mesh& mesh : {make_cube(), make_grid(4), pinched}) {
    const MeshTopology topology = build_topology(mesh);
    for (int v = 0; v < mesh.vertex_count(); ++v) {
      std::vector<int> holding;
      for (int f = 0; f < mesh.face_count(); ++f) {
        const Triangle& t = mesh.triangles[f];
        if (std::find(t.begin(), t.end(), v) != t.end()) holding.push_back(f);
      }
      std::vector<int> visited;
      for_each_face_of_vertex(topology, v, [&](int face) { visited.push_back(face); });
      std::sort(visited.begin(), visited.end());
      EXPECT_EQ(visited, holding) << v;
      EXPECT_EQ(faces_of_vertex(topology, v), holding) << v;
    }
  }
  EXPECT_TRUE(build_topology(make_grid(4)).listed_vertices.empty());
  const MeshTopology topology = build_topology(pinched);
  EXPECT_TRUE(
      std::binary_search(topology.listed_vertices.begin(), topology.listed_vertices.end(), 0));
  EXPECT_EQ(topology.vertex_halfedge[0], kListedFaces);
  EXPECT_EQ(topology.vertex_halfedge[5], kListedFaces);
  EXPECT_EQ(topology.nonmanifold_vertices, (std::vector<int>{0, 1, 5}));
}

TEST(Topology, MisorientedEdgeIsCounted) {
  const Mesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 1, 2}, {1, 3, 2}});
  EXPECT_EQ(build_topology(mesh).misoriented_edge_count, 0);
  const Mesh flipped =
      make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 1, 2}, {1, 2, 3}});
  const MeshTopology topology = build_topology(flipped);
  EXPECT_EQ(topology.misoriented_edge_count, 1);
  EXPECT_TRUE(topology.nonmanifold_vertices.empty());
}

// Without a stored edge list, the half-edges of an edge are found where they lie: three faces on
// edge (0, 1), a misoriented pair on (0, 2) and open edges. Each edge's first half-edge is the one
// that counts it, as in the listed edges; components and fans join across every edge.
TEST(Topology, EdgesAreFoundWithoutAList) {
  const Mesh mesh =
      make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}, {-1, 1, 0}},
                {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {2, 0, 5}});
  const MeshTopology topology = build_topology(mesh);
  const MeshEdges edges = build_edges(mesh, topology);
  EXPECT_EQ(topology.edge_count, static_cast<int>(edges.edges.size()));
  EXPECT_EQ(topology.nonmanifold_edge_count, 1);
  EXPECT_EQ(topology.misoriented_edge_count, 1);
  EXPECT_EQ(face_components(mesh, topology).count, 1);
  int firsts = 0;
  for (int h = 0; h < 3 * mesh.face_count(); ++h) {
    const Edge& edge = edges.edges[edges.halfedge_edge[h]];
    const std::vector<int> listed(edges.edge_halfedges.begin() + edge.first,
                                  edges.edge_halfedges.begin() + edge.first + edge.count);
    EXPECT_EQ(halfedges_on_edge(mesh, topology, h), listed) << h;
    EXPECT_EQ(is_first_halfedge_of_edge(mesh, topology, h), listed.front() == h) << h;
    firsts += is_first_halfedge_of_edge(mesh, topology, h);
  }
  EXPECT_EQ(firsts, topology.edge_count);
  EXPECT_EQ(halfedges_on_edge(mesh, topology, 0).size(), 3u);  // (0, 1)
  // Vertex 2's faces 0 and 3 meet at the misoriented edge (0, 2): one fan.
  EXPECT_EQ(
      std::count(topology.nonmanifold_vertices.begin(), topology.nonmanifold_vertices.end(), 2), 0);
}

// Where loops of one component touch at a vertex, fills can join its fans: the vertex is fillable.
// Where two components touch, or faces meet at a non-manifold edge, it is not.
TEST(Topology, UnfillableVerticesAreWhereNoFillMakesAManifold) {
  // A 3x3 grid without its centre quad and its corner quad (2, 2): the hole and the border touch
  // at vertex 10, one component.
  Mesh grid = make_grid(3);
  testing::remove_grid_quad(grid, 3, 2, 2);
  testing::remove_grid_quad(grid, 3, 1, 1);
  const MeshTopology grid_topology = build_topology(grid);
  EXPECT_EQ(grid_topology.nonmanifold_vertices, (std::vector<int>{10}));
  EXPECT_TRUE(unfillable_vertices(grid, grid_topology).empty());

  const Mesh bowtie = make_mesh({{0, 0, 0}, {-1, -1, 0}, {-1, 1, 0}, {1, 1, 0}, {1, -1, 0}},
                                {{0, 2, 1}, {0, 4, 3}});  // two components
  EXPECT_EQ(unfillable_vertices(bowtie, build_topology(bowtie)), (std::vector<int>{0}));

  const Mesh fan = make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}},
                             {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});  // three faces on (0, 1)
  EXPECT_EQ(unfillable_vertices(fan, build_topology(fan)), (std::vector<int>{0, 1}));
}

TEST(Topology, DefectsAreCounted) {
  Mesh cube = make_cube();
  EXPECT_FALSE(find_defects(cube, build_topology(cube)).any());
  cube.triangles.push_back(cube.triangles[3]);                // duplicated
  cube.positions.push_back(cube.positions[0]);                // a vertex on vertex 0
  cube.triangles.push_back({0, 1, cube.vertex_count() - 1});  // degenerate, on edge (0, 1)
  cube = make_mesh(cube.positions, cube.triangles);
  const MeshDefects defects = find_defects(cube, build_topology(cube));
  EXPECT_EQ(defects.duplicated_faces, 1);
  EXPECT_EQ(defects.degenerate_faces, 1);
  EXPECT_EQ(defects.nonmanifold_edges, 4);  // the duplicate's three edges and (0, 1)
  EXPECT_EQ(describe(defects).substr(0, 22), "4 non-manifold edges, ");
  EXPECT_NE(describe(defects).find("1 duplicated face, 1 degenerate face"), std::string::npos)
      << describe(defects);
}

// A grid of 120 000 faces, large enough to be built in parallel ranges of vertices, joined: every
// edge once, in (lower, higher) vertex order, each half-edge on its edge and paired with the
// half-edge that runs the other way.
TEST(Topology, RangesBuiltInParallelJoinIntoOneTopology) {
  const Mesh grid = testing::make_grid(245);  // 2 · 245² faces
  ASSERT_GE(grid.face_count(), 100000);
  const MeshTopology topology = build_topology(grid);
  EXPECT_EQ(topology.edge_count, 3 * 245 * 245 + 2 * 245);  // V + F − 1 on a disc
  const MeshEdges edges = build_edges(grid, topology);
  ASSERT_EQ(edges.edges.size(), static_cast<size_t>(topology.edge_count));
  for (size_t e = 0; e < edges.edges.size(); ++e) {
    const Edge& edge = edges.edges[e];
    if (e > 0) {
      const Edge& previous = edges.edges[e - 1];
      ASSERT_LT(std::make_pair(previous.v0, previous.v1), std::make_pair(edge.v0, edge.v1)) << e;
    }
    for (int i = edge.first; i < edge.first + edge.count; ++i) {
      const int h = edges.edge_halfedges[i];
      ASSERT_EQ(edges.halfedge_edge[h], static_cast<int>(e));
      const int source = topology.halfedge_source(grid, h),
                target = topology.halfedge_target(grid, h);
      ASSERT_EQ(std::min(source, target), edge.v0);
      ASSERT_EQ(std::max(source, target), edge.v1);
      const int opposite = topology.opposite[h];
      ASSERT_EQ(opposite >= 0, edge.count == 2);
      if (opposite >= 0) {
        ASSERT_EQ(topology.halfedge_source(grid, opposite), target);
      }
    }
  }
  EXPECT_TRUE(topology.nonmanifold_vertices.empty());
  EXPECT_FALSE(find_defects(grid, topology).any());
}

// A vertex's normal from its faces alone is the mesh-wide computation's, to the bit.
TEST(Topology, VertexNormalIsTheMeshWideNormal) {
  Mesh sphere = testing::make_sphere(8);
  for (size_t v = 0; v < sphere.positions.size(); ++v) {
    sphere.positions[v] *= 1 + 0.1 * std::sin(3.0 * static_cast<double>(v));
  }
  const MeshTopology topology = build_topology(sphere);
  const std::vector<Vec3> normals = vertex_normals_from_faces(sphere);
  for (int v = 0; v < sphere.vertex_count(); ++v) {
    ASSERT_EQ(vertex_normal(sphere, topology, v), normals[v]) << v;
  }
}

}  // namespace
}  // namespace rangefill
