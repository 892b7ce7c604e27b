// Adjacency of a triangle mesh: half-edges, their opposites and the faces around each vertex; the
// list of undirected edges on request. Built in O(V + E): each edge's half-edges chained at its
// lower vertex (in the array that then holds the opposites), ranges of vertices in parallel for
// a large mesh (the same result at any thread count); no hashing. The topology is 3 ints a face
// and 1 a vertex: the faces around a vertex are found by walking round it through the opposites,
// listed only where no walk reaches them all.
#pragma once

#include <algorithm>
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
  // Per vertex: a half-edge leaving it, where the walk round its faces starts; kNoFaces, or
  // kListedFaces for a vertex whose faces no walk reaches (several fans, a non-manifold edge).
  std::vector<int> vertex_halfedge;
  std::vector<int> listed_vertices;       // the kListedFaces vertices, ascending
  std::vector<int> listed_face_offsets;   // CSR over listed_vertices, size + 1
  std::vector<int> listed_faces;          // their faces, ascending
  std::vector<int> nonmanifold_vertices;  // vertices whose faces form more than one fan
  int edge_count = 0;                     // undirected edges
  int nonmanifold_edge_count = 0;         // edges with more than two faces
  int misoriented_edge_count = 0;         // edges whose two faces disagree in orientation
  int duplicated_face_count = 0;          // faces on the same three vertices as an earlier one

  static int halfedge_source(const Mesh& mesh, int h) { return mesh.triangles[h / 3][h % 3]; }
  static int halfedge_target(const Mesh& mesh, int h) {
    return mesh.triangles[h / 3][(h % 3 + 1) % 3];
  }
};

/// Values of MeshTopology::vertex_halfedge other than a half-edge.
inline constexpr int kNoFaces = -1;
inline constexpr int kListedFaces = -2;

/// Builds the adjacency. Precondition: validate_mesh(mesh) passes.
MeshTopology build_topology(const Mesh& mesh);

/// Calls visit(face) once for each face of the fan of half-edge `start` (which leaves a vertex v)
/// reached through two-face edges at v: round v against the orientation, and when the fan is open,
/// from `start` with the orientation. O(faces visited).
template <typename Visit>
void for_each_face_of_fan(const MeshTopology& topology, int start, Visit visit) {
  visit(halfedge_face(start));
  // Against the orientation: across the edge entering v, to the half-edge leaving v beyond it.
  int h = topology.opposite[prev_halfedge(start)];
  for (; h >= 0 && h != start; h = topology.opposite[prev_halfedge(h)]) visit(halfedge_face(h));
  if (h == start) return;  // closed round
  // With the orientation: across the edge leaving v, to the half-edge entering v beyond it.
  for (h = topology.opposite[start]; h >= 0; h = topology.opposite[next_halfedge(h)]) {
    visit(halfedge_face(h));
  }
}

/// Calls visit(face) once for each face around vertex v: round its fan from
/// topology.vertex_halfedge[v], else in ascending order from its list. O(valence), O(log) more
/// for a listed vertex.
template <typename Visit>
void for_each_face_of_vertex(const MeshTopology& topology, int v, Visit visit) {
  const int start = topology.vertex_halfedge[v];
  if (start >= 0) {
    for_each_face_of_fan(topology, start, visit);
  } else if (start == kListedFaces) {
    const auto& listed = topology.listed_vertices;
    const auto i = std::lower_bound(listed.begin(), listed.end(), v) - listed.begin();
    for (int k = topology.listed_face_offsets[i]; k < topology.listed_face_offsets[i + 1]; ++k) {
      visit(topology.listed_faces[k]);
    }
  }
}

/// The faces around vertex v, ascending.
std::vector<int> faces_of_vertex(const MeshTopology& topology, int v);

/// Connected components of faces, joined through their edges (misoriented and non-manifold ones
/// too).
struct FaceComponents {
  int count = 0;
  std::vector<int> of_face;  // per face, in [0, count)
};

/// The components of `mesh`'s faces. Precondition: `topology` was built from `mesh`.
FaceComponents face_components(const Mesh& mesh, const MeshTopology& topology);

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

/// Whether a face has the edge between vertices `a` and `b`, either way round.
bool has_edge(const Mesh& mesh, const MeshTopology& topology, int a, int b);

/// The faces within `rings` rings of `vertices`: ring 1 holds the faces of the vertices, ring k+1
/// those of the vertices of ring k. Ascending.
std::vector<int> faces_within_rings(const Mesh& mesh, const MeshTopology& topology,
                                    const std::vector<int>& vertices, int rings);

}  // namespace rangefill
