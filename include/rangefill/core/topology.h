// Adjacency of a triangle mesh: half-edges, their opposites and vertex-to-face incidence; the list
// of undirected edges on request. Built in O(V + E): each edge grouped at its lower vertex from
// that vertex's faces, ranges of vertices in parallel for a large mesh (the same result at any
// thread count); no hashing. The topology a repair holds is 4 ints a face and 1 a vertex.
#pragma once

#include <string>
#include <vector>

#include "rangefill/core/mesh.h"

namespace rangefill {

/// Half-edge h = 3·f + i of face f runs from corner i to corner (i + 1) % 3 (face orientation).
inline int halfedge_face(int h) {
  return h / 3;
}
inline int next_halfedge(int h) {
  return h - h % 3 + (h + 1) % 3;
}
inline int prev_halfedge(int h) {
  return h - h % 3 + (h + 2) % 3;
}

/// Value of MeshTopology::opposite for a half-edge whose edge has no second face.
inline constexpr int kBoundary = -1;
/// Value of MeshTopology::opposite for a half-edge whose edge is shared by more than two faces, or
/// by two faces that traverse it in the same direction (inconsistent orientation).
inline constexpr int kNonManifold = -2;

struct MeshTopology {
  std::vector<int> opposite;  // per half-edge: the opposite half-edge, kBoundary or kNonManifold
  std::vector<int> vertex_face_offsets;   // CSR, size V + 1
  std::vector<int> vertex_faces;          // faces around each vertex, ascending
  std::vector<int> nonmanifold_vertices;  // vertices whose faces form more than one fan
  int edge_count = 0;                     // undirected edges
  int nonmanifold_edge_count = 0;         // edges with more than two faces
  int misoriented_edge_count = 0;         // edges whose two faces disagree in orientation
  int duplicated_face_count = 0;          // faces on the same three vertices as an earlier one
  int component_count = 0;                // connected components of faces (through edges)
  std::vector<int> face_component;        // per face, in [0, component_count)

  int halfedge_source(const Mesh& mesh, int h) const { return mesh.triangles[h / 3][h % 3]; }
  int halfedge_target(const Mesh& mesh, int h) const {
    return mesh.triangles[h / 3][(h % 3 + 1) % 3];
  }
  int faces_of_vertex_begin(int v) const { return vertex_face_offsets[v]; }
  int faces_of_vertex_end(int v) const { return vertex_face_offsets[v + 1]; }
};

/// Builds the adjacency. Precondition: validate_mesh(mesh) passes.
MeshTopology build_topology(const Mesh& mesh);

/// One undirected edge and the half-edges that lie on it.
struct Edge {
  int v0, v1;  // v0 < v1
  int first;   // offset into MeshEdges::edge_halfedges
  int count;   // number of faces on the edge
};

/// The undirected edges of a mesh, ordered by (lower vertex, higher vertex), with their half-edges.
struct MeshEdges {
  std::vector<Edge> edges;
  std::vector<int> edge_halfedges;  // grouped by edge, see Edge::first / count
  std::vector<int> halfedge_edge;   // per half-edge: index into `edges`
};

/// Lists the edges of `mesh`. Precondition: `topology` was built from `mesh`.
MeshEdges build_edges(const Mesh& mesh, const MeshTopology& topology);

/// The half-edges on the undirected edge of half-edge h, h among them, ascending: h and its
/// opposite, h alone on the boundary, two or more at a kNonManifold half-edge (found among the
/// faces of h's source, O(valence)).
std::vector<int> halfedges_on_edge(const Mesh& mesh, const MeshTopology& topology, int h);

/// Whether h is the lowest half-edge on its edge: visiting those visits every edge once.
bool is_first_halfedge_of_edge(const Mesh& mesh, const MeshTopology& topology, int h);

/// What keeps a mesh from being a clean 2-manifold, its boundary aside.
struct MeshDefects {
  int nonmanifold_edges = 0;     // edges with more than two faces
  int misoriented_edges = 0;     // edges whose two faces disagree in orientation
  int nonmanifold_vertices = 0;  // vertices whose faces form more than one fan
  int duplicated_faces = 0;      // faces on the same three vertices as an earlier one
  int degenerate_faces = 0;      // is_degenerate (mesh.h)
  bool any() const;
};

/// Counts the defects of `mesh`.
MeshDefects find_defects(const Mesh& mesh, const MeshTopology& topology);

/// The non-zero counts in words, comma-separated ("2 non-manifold edges, 1 duplicated face").
std::string describe(const MeshDefects& defects);

/// Vertices, ascending, where no fill can make the surface a manifold, so that a fill must not use
/// them: those on an edge of kNonManifold half-edges (more than two faces, or misoriented, as the
/// edges of a duplicated face are), and non-manifold vertices other than where open fans of one
/// component meet (loops touching at a vertex, whose fills join the fans into one).
std::vector<int> unfillable_vertices(const Mesh& mesh, const MeshTopology& topology);

/// The unit normal of vertex v: the sum of its faces' cross products (area-weighted), normalised;
/// zero when they cancel. vertex_normals_from_faces(mesh)[v] to the bit, in O(valence).
Vec3 vertex_normal(const Mesh& mesh, const MeshTopology& topology, int v);

/// The half-edge from vertex `from` to vertex `to` (the first in face order), or -1 if no face
/// has it. O(valence).
int find_halfedge(const Mesh& mesh, const MeshTopology& topology, int from, int to);

}  // namespace rangefill
