#include "rangefill/core/topology.h"

#include <algorithm>
#include <numeric>

#include "rangefill/core/parallel.h"

namespace rangefill {

namespace {

int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

// Vertex-to-face incidence in CSR form, faces ascending.
void build_vertex_faces(const Mesh& mesh, MeshTopology& topology) {
  const int vertex_count = mesh.vertex_count();
  topology.vertex_face_offsets.assign(static_cast<size_t>(vertex_count) + 1, 0);
  for (const Triangle& t : mesh.triangles) {
    for (int v : t) ++topology.vertex_face_offsets[v + 1];
  }
  std::partial_sum(topology.vertex_face_offsets.begin(), topology.vertex_face_offsets.end(),
                   topology.vertex_face_offsets.begin());
  topology.vertex_faces.resize(topology.vertex_face_offsets.back());
  std::vector<int> cursor(topology.vertex_face_offsets.begin(),
                          topology.vertex_face_offsets.end() - 1);
  for (int f = 0; f < mesh.face_count(); ++f) {
    for (int v : mesh.triangles[f]) topology.vertex_faces[cursor[v]++] = f;
  }
}

// The faces, among those on the half-edges upward[begin, end) of one edge, with the three
// vertices of an earlier face on it, each counted on its first edge (h % 3 == 0): a face on the
// same vertices as an earlier one shares its first edge with it.
int duplicated_faces(const Mesh& mesh, const std::vector<std::pair<int, int>>& upward, size_t begin,
                     size_t end) {
  if (end - begin < 2) return 0;
  auto sorted_corners = [&](int face) {
    Triangle t = mesh.triangles[face];
    std::sort(t.begin(), t.end());
    return t;
  };
  int count = 0;
  for (size_t i = begin; i < end; ++i) {
    const int h = upward[i].second;
    if (h % 3 != 0) continue;
    for (size_t j = begin; j < end; ++j) {
      const int other = halfedge_face(upward[j].second);
      if (other < halfedge_face(h) && sorted_corners(other) == sorted_corners(halfedge_face(h))) {
        ++count;
        break;
      }
    }
  }
  return count;
}

// The edges whose lower end lies in a range of vertices, built apart from the others.
struct EdgesOfRange {
  std::vector<Edge> edges;  // Edge::first into edge_halfedges below
  std::vector<int> edge_halfedges;
  int nonmanifold_edges = 0, misoriented_edges = 0, duplicated_faces = 0;
};

// The edges whose lower end v is in [first_vertex, last_vertex), ordered by (v, higher vertex,
// half-edge); pairs their opposites in `topology` and gives each of their half-edges the edge's
// index in the range. The half-edges of the edges whose lower end is v are among v's faces.
EdgesOfRange build_edges_of_range(const Mesh& mesh, MeshTopology& topology, int first_vertex,
                                  int last_vertex) {
  auto source = [&](int h) { return topology.halfedge_source(mesh, h); };
  auto target = [&](int h) { return topology.halfedge_target(mesh, h); };
  EdgesOfRange range;
  // A closed mesh has some 3 edges a vertex, each with 2 half-edges.
  range.edges.reserve(3 * static_cast<size_t>(last_vertex - first_vertex));
  range.edge_halfedges.reserve(6 * static_cast<size_t>(last_vertex - first_vertex));
  std::vector<std::pair<int, int>> upward;  // (higher vertex, half-edge) of the edges leaving v up
  for (int v = first_vertex; v < last_vertex; ++v) {
    upward.clear();
    for (int i = topology.faces_of_vertex_begin(v); i < topology.faces_of_vertex_end(v); ++i) {
      const int face = topology.vertex_faces[i];
      for (int h = 3 * face; h < 3 * face + 3; ++h) {
        if (std::min(source(h), target(h)) == v)
          upward.emplace_back(std::max(source(h), target(h)), h);
      }
    }
    std::sort(upward.begin(), upward.end());
    for (size_t begin = 0; begin < upward.size();) {
      size_t end = begin + 1;
      while (end < upward.size() && upward[end].first == upward[begin].first) ++end;
      const int edge = static_cast<int>(range.edges.size());
      const int first = static_cast<int>(range.edge_halfedges.size());
      range.edges.push_back({v, upward[begin].first, first, static_cast<int>(end - begin)});
      for (size_t i = begin; i < end; ++i) {
        topology.halfedge_edge[upward[i].second] = edge;
        range.edge_halfedges.push_back(upward[i].second);
      }
      range.duplicated_faces += duplicated_faces(mesh, upward, begin, end);
      if (end - begin == 2) {
        const int a = upward[begin].second, b = upward[begin + 1].second;
        if (source(a) == target(b)) {
          topology.opposite[a] = b;
          topology.opposite[b] = a;
        } else {
          topology.opposite[a] = topology.opposite[b] = kNonManifold;
          ++range.misoriented_edges;
        }
      } else if (end - begin > 2) {
        for (size_t i = begin; i < end; ++i) topology.opposite[upward[i].second] = kNonManifold;
        ++range.nonmanifold_edges;
      }
      begin = end;
    }
  }
  return range;
}

// Groups half-edges into undirected edges, ordered by (lower vertex, higher vertex, half-edge),
// and pairs opposites: ranges of vertices in parallel, joined in order (the same at any thread
// count).
void build_edges(const Mesh& mesh, MeshTopology& topology) {
  const int halfedge_count = 3 * mesh.face_count();
  topology.opposite.assign(halfedge_count, kBoundary);
  topology.halfedge_edge.assign(halfedge_count, -1);
  const int vertices = mesh.vertex_count();
  std::vector<EdgesOfRange> ranges(kMeshRanges);
  parallel_for(kMeshRanges, mesh_pass_threads(mesh.face_count()), [&](int r) {
    ranges[r] = build_edges_of_range(mesh, topology, range_begin(vertices, r),
                                     range_begin(vertices, r + 1));
  });
  std::vector<int> edge_offsets(kMeshRanges + 1, 0), halfedge_offsets(kMeshRanges + 1, 0);
  for (int r = 0; r < kMeshRanges; ++r) {
    edge_offsets[r + 1] = edge_offsets[r] + static_cast<int>(ranges[r].edges.size());
    halfedge_offsets[r + 1] =
        halfedge_offsets[r] + static_cast<int>(ranges[r].edge_halfedges.size());
    topology.nonmanifold_edge_count += ranges[r].nonmanifold_edges;
    topology.misoriented_edge_count += ranges[r].misoriented_edges;
    topology.duplicated_face_count += ranges[r].duplicated_faces;
  }
  topology.edges.resize(edge_offsets.back());
  topology.edge_halfedges.resize(halfedge_offsets.back());
  parallel_for(kMeshRanges, mesh_pass_threads(mesh.face_count()), [&](int r) {
    EdgesOfRange& range = ranges[r];
    for (int h : range.edge_halfedges) topology.halfedge_edge[h] += edge_offsets[r];
    for (Edge& edge : range.edges) edge.first += halfedge_offsets[r];
    std::copy(range.edges.begin(), range.edges.end(), topology.edges.begin() + edge_offsets[r]);
    std::copy(range.edge_halfedges.begin(), range.edge_halfedges.end(),
              topology.edge_halfedges.begin() + halfedge_offsets[r]);
    range = EdgesOfRange();
  });
}

// Components of faces joined through manifold edges (and misoriented or non-manifold ones).
void build_components(const Mesh& mesh, MeshTopology& topology) {
  std::vector<int> parent(mesh.face_count());
  std::iota(parent.begin(), parent.end(), 0);
  for (const Edge& edge : topology.edges) {
    const int first_face = halfedge_face(topology.edge_halfedges[edge.first]);
    for (int i = 1; i < edge.count; ++i) {
      const int face = halfedge_face(topology.edge_halfedges[edge.first + i]);
      parent[find_root(parent, face)] = find_root(parent, first_face);
    }
  }
  topology.face_component.assign(mesh.face_count(), -1);
  std::vector<int> root_component(mesh.face_count(), -1);
  topology.component_count = 0;
  for (int f = 0; f < mesh.face_count(); ++f) {
    const int root = find_root(parent, f);
    if (root_component[root] < 0) root_component[root] = topology.component_count++;
    topology.face_component[f] = root_component[root];
  }
}

// The faces around vertex v reached from its first face by crossing manifold edges at v, both
// ways round (at most all of them).
int faces_in_first_fan(const Mesh& mesh, const MeshTopology& topology, int v) {
  const int first = topology.vertex_faces[topology.vertex_face_offsets[v]];
  int leaving = 3 * first;  // the half-edge of `first` that leaves v
  while (topology.halfedge_source(mesh, leaving) != v) ++leaving;
  const int degree = topology.vertex_face_offsets[v + 1] - topology.vertex_face_offsets[v];
  int count = 1;
  // Against the orientation: across the edge entering v, to the face where it leaves v.
  for (int h = topology.opposite[prev_halfedge(leaving)]; h >= 0 && count <= degree;
       h = topology.opposite[prev_halfedge(h)]) {
    if (halfedge_face(h) == first) return count;  // closed round
    ++count;
  }
  // With the orientation: across the edge leaving v, to the face where it enters v.
  for (int h = topology.opposite[leaving]; h >= 0 && count <= degree;
       h = topology.opposite[next_halfedge(h)]) {
    ++count;
  }
  return count;
}

// The fans of faces around vertex v: its faces linked through the two-face edges at v. `parent` is
// scratch space. One walk round v settles the common case (a single fan through manifold edges).
int count_fans(const Mesh& mesh, const MeshTopology& topology, int v, std::vector<int>& parent) {
  const int begin = topology.vertex_face_offsets[v];
  const int end = topology.vertex_face_offsets[v + 1];
  if (begin == end) return 0;
  if (faces_in_first_fan(mesh, topology, v) == end - begin) return 1;
  parent.resize(end - begin);
  std::iota(parent.begin(), parent.end(), 0);
  int fans = end - begin;
  for (int i = begin; i < end; ++i) {
    const int face = topology.vertex_faces[i];
    for (int corner = 0; corner < 3; ++corner) {
      const int h = 3 * face + corner;
      if (topology.halfedge_source(mesh, h) != v) continue;
      // The two edges of `face` at v are the one leaving v and the one entering it.
      for (int at_v : {h, prev_halfedge(h)}) {
        const Edge& edge = topology.edges[topology.halfedge_edge[at_v]];
        if (edge.count != 2) continue;
        const int h0 = topology.edge_halfedges[edge.first];
        const int neighbour =
            halfedge_face(h0 == at_v ? topology.edge_halfedges[edge.first + 1] : h0);
        const auto other = std::lower_bound(topology.vertex_faces.begin() + begin,
                                            topology.vertex_faces.begin() + end, neighbour);
        const int a = find_root(parent, i - begin);
        const int b =
            find_root(parent, static_cast<int>(other - topology.vertex_faces.begin()) - begin);
        if (a != b) {
          parent[a] = b;
          --fans;
        }
      }
    }
  }
  return fans;
}

// A vertex is non-manifold when its faces form more than one fan (a pinch, or faces meeting at a
// non-manifold edge). Ranges of vertices in parallel, joined in order.
void find_nonmanifold_vertices(const Mesh& mesh, MeshTopology& topology) {
  const int vertices = mesh.vertex_count();
  std::vector<std::vector<int>> found(kMeshRanges);
  parallel_for(kMeshRanges, mesh_pass_threads(mesh.face_count()), [&](int r) {
    std::vector<int> parent;
    for (int v = range_begin(vertices, r); v < range_begin(vertices, r + 1); ++v) {
      if (count_fans(mesh, topology, v, parent) > 1) found[r].push_back(v);
    }
  });
  for (const std::vector<int>& vertices : found) {
    topology.nonmanifold_vertices.insert(topology.nonmanifold_vertices.end(), vertices.begin(),
                                         vertices.end());
  }
}

}  // namespace

MeshTopology build_topology(const Mesh& mesh) {
  MeshTopology topology;
  build_vertex_faces(mesh, topology);
  build_edges(mesh, topology);
  build_components(mesh, topology);
  find_nonmanifold_vertices(mesh, topology);
  return topology;
}

Vec3 vertex_normal(const Mesh& mesh, const MeshTopology& topology, int v) {
  Vec3 normal = Vec3::Zero();  // summed in face order, as vertex_normals_from_faces does
  for (int i = topology.faces_of_vertex_begin(v); i < topology.faces_of_vertex_end(v); ++i) {
    normal += triangle_cross(mesh, topology.vertex_faces[i]);
  }
  const double length = normal.norm();
  if (length > 0) normal /= length;
  return normal;
}

int find_halfedge(const Mesh& mesh, const MeshTopology& topology, int from, int to) {
  for (int i = topology.faces_of_vertex_begin(from); i < topology.faces_of_vertex_end(from); ++i) {
    const int face = topology.vertex_faces[i];
    for (int corner = 0; corner < 3; ++corner) {
      const int h = 3 * face + corner;
      if (topology.halfedge_source(mesh, h) == from && topology.halfedge_target(mesh, h) == to) {
        return h;
      }
    }
  }
  return -1;
}

}  // namespace rangefill

namespace rangefill {

bool MeshDefects::any() const {
  return nonmanifold_edges + misoriented_edges + nonmanifold_vertices + duplicated_faces +
             degenerate_faces >
         0;
}

std::string describe(const MeshDefects& defects) {
  std::string text;
  auto add = [&](int count, const std::string& one, const std::string& several) {
    if (count == 0) return;
    text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + (count == 1 ? one : several);
  };
  add(defects.nonmanifold_edges, "non-manifold edge", "non-manifold edges");
  add(defects.misoriented_edges, "misoriented edge", "misoriented edges");
  add(defects.nonmanifold_vertices, "non-manifold vertex", "non-manifold vertices");
  add(defects.duplicated_faces, "duplicated face", "duplicated faces");
  add(defects.degenerate_faces, "degenerate face", "degenerate faces");
  return text;
}

MeshDefects find_defects(const Mesh& mesh, const MeshTopology& topology) {
  MeshDefects defects;
  defects.nonmanifold_edges = topology.nonmanifold_edge_count;
  defects.misoriented_edges = topology.misoriented_edge_count;
  defects.nonmanifold_vertices = static_cast<int>(topology.nonmanifold_vertices.size());
  defects.duplicated_faces = topology.duplicated_face_count;
  const int faces = mesh.face_count();
  std::vector<int> degenerate(kMeshRanges, 0);
  parallel_for(kMeshRanges, mesh_pass_threads(faces), [&](int r) {
    for (int f = range_begin(faces, r); f < range_begin(faces, r + 1); ++f) {
      degenerate[r] += is_degenerate(mesh, f);
    }
  });
  defects.degenerate_faces = std::accumulate(degenerate.begin(), degenerate.end(), 0);
  return defects;
}

std::vector<int> unfillable_vertices(const Mesh& mesh, const MeshTopology& topology) {
  std::vector<char> unfillable(mesh.vertex_count(), 0);
  for (size_t h = 0; h < topology.opposite.size(); ++h) {
    if (topology.opposite[h] == kNonManifold) {
      unfillable[topology.halfedge_source(mesh, static_cast<int>(h))] = 1;
      unfillable[topology.halfedge_target(mesh, static_cast<int>(h))] = 1;
    }
  }
  // Elsewhere a vertex of several fans, each open (one boundary half-edge leaves it), all of one
  // component, is where loops touch: fills of those loops join its fans into one.
  std::vector<int> parent;
  for (int v : topology.nonmanifold_vertices) {
    if (unfillable[v]) continue;
    int leaving_boundary = 0;
    bool one_component = true;
    const int first_face = topology.vertex_faces[topology.faces_of_vertex_begin(v)];
    for (int i = topology.faces_of_vertex_begin(v); i < topology.faces_of_vertex_end(v); ++i) {
      const int face = topology.vertex_faces[i];
      one_component =
          one_component && topology.face_component[face] == topology.face_component[first_face];
      for (int corner = 0; corner < 3; ++corner) {
        const int h = 3 * face + corner;
        leaving_boundary +=
            topology.halfedge_source(mesh, h) == v && topology.opposite[h] == kBoundary;
      }
    }
    unfillable[v] = !one_component || leaving_boundary != count_fans(mesh, topology, v, parent);
  }
  std::vector<int> vertices;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (unfillable[v]) vertices.push_back(v);
  }
  return vertices;
}

}  // namespace rangefill
