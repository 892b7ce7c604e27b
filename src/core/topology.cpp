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

// The half-edges of v's faces on the edges whose lower end is v, as (higher end, half-edge),
// sorted: each run of one higher end is an edge, its half-edges ascending.
void upward_halfedges(const Mesh& mesh, const MeshTopology& topology, int v,
                      std::vector<std::pair<int, int>>& upward) {
  upward.clear();
  for (int i = topology.faces_of_vertex_begin(v); i < topology.faces_of_vertex_end(v); ++i) {
    const int face = topology.vertex_faces[i];
    for (int h = 3 * face; h < 3 * face + 3; ++h) {
      const int source = topology.halfedge_source(mesh, h);
      const int target = topology.halfedge_target(mesh, h);
      if (std::min(source, target) == v) upward.emplace_back(std::max(source, target), h);
    }
  }
  std::sort(upward.begin(), upward.end());
}

// Calls on_edge(begin, end) for each run upward[begin, end) of one higher end: each edge.
template <typename OnEdge>
void for_each_edge_run(const std::vector<std::pair<int, int>>& upward, OnEdge on_edge) {
  for (size_t begin = 0; begin < upward.size();) {
    size_t end = begin + 1;
    while (end < upward.size() && upward[end].first == upward[begin].first) ++end;
    on_edge(begin, end);
    begin = end;
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

// What the edges whose lower end lies in a range of vertices count.
struct EdgeCounts {
  int edges = 0, nonmanifold_edges = 0, misoriented_edges = 0, duplicated_faces = 0;
};

// Pairs the opposite half-edges of the edges whose lower end is in [first_vertex, last_vertex)
// and counts those edges.
EdgeCounts pair_opposites_of_range(const Mesh& mesh, MeshTopology& topology, int first_vertex,
                                   int last_vertex) {
  EdgeCounts counts;
  std::vector<std::pair<int, int>> upward;
  for (int v = first_vertex; v < last_vertex; ++v) {
    upward_halfedges(mesh, topology, v, upward);
    for_each_edge_run(upward, [&](size_t begin, size_t end) {
      ++counts.edges;
      counts.duplicated_faces += duplicated_faces(mesh, upward, begin, end);
      if (end - begin == 2) {
        const int a = upward[begin].second, b = upward[begin + 1].second;
        if (topology.halfedge_source(mesh, a) == topology.halfedge_target(mesh, b)) {
          topology.opposite[a] = b;
          topology.opposite[b] = a;
        } else {
          topology.opposite[a] = topology.opposite[b] = kNonManifold;
          ++counts.misoriented_edges;
        }
      } else if (end - begin > 2) {
        for (size_t i = begin; i < end; ++i) topology.opposite[upward[i].second] = kNonManifold;
        ++counts.nonmanifold_edges;
      }
    });
  }
  return counts;
}

// Pairs opposite half-edges and counts the edges: ranges of vertices in parallel, each writing the
// half-edges of its own edges (the same at any thread count).
void pair_opposites(const Mesh& mesh, MeshTopology& topology) {
  topology.opposite.assign(3 * static_cast<size_t>(mesh.face_count()), kBoundary);
  const int vertices = mesh.vertex_count();
  std::vector<EdgeCounts> ranges(kMeshRanges);
  parallel_for(kMeshRanges, mesh_pass_threads(mesh.face_count()), [&](int r) {
    ranges[r] = pair_opposites_of_range(mesh, topology, range_begin(vertices, r),
                                        range_begin(vertices, r + 1));
  });
  for (const EdgeCounts& range : ranges) {
    topology.edge_count += range.edges;
    topology.nonmanifold_edge_count += range.nonmanifold_edges;
    topology.misoriented_edge_count += range.misoriented_edges;
    topology.duplicated_face_count += range.duplicated_faces;
  }
}

// Components of faces joined through manifold edges (and misoriented or non-manifold ones).
void build_components(const Mesh& mesh, MeshTopology& topology) {
  std::vector<int> parent(mesh.face_count());
  std::iota(parent.begin(), parent.end(), 0);
  for (int h = 0; h < static_cast<int>(topology.opposite.size()); ++h) {
    const auto join = [&](int other) {
      parent[find_root(parent, halfedge_face(other))] = find_root(parent, halfedge_face(h));
    };
    const int opposite = topology.opposite[h];
    if (opposite > h) join(opposite);
    if (opposite == kNonManifold) {
      for (int other : halfedges_on_edge(mesh, topology, h)) join(other);
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
        int across = topology.opposite[at_v];
        if (across == kNonManifold) {  // linked too when its edge has two misoriented faces
          const std::vector<int> on_edge = halfedges_on_edge(mesh, topology, at_v);
          across = on_edge.size() == 2 ? on_edge[on_edge[0] == at_v] : kBoundary;
        }
        if (across < 0) continue;
        const int neighbour = halfedge_face(across);
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
  pair_opposites(mesh, topology);
  build_components(mesh, topology);
  find_nonmanifold_vertices(mesh, topology);
  return topology;
}

MeshEdges build_edges(const Mesh& mesh, const MeshTopology& topology) {
  MeshEdges edges;
  edges.edges.reserve(topology.edge_count);
  edges.edge_halfedges.reserve(topology.opposite.size());
  edges.halfedge_edge.assign(topology.opposite.size(), -1);
  std::vector<std::pair<int, int>> upward;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    upward_halfedges(mesh, topology, v, upward);
    for_each_edge_run(upward, [&](size_t begin, size_t end) {
      const int edge = static_cast<int>(edges.edges.size());
      edges.edges.push_back({v, upward[begin].first, static_cast<int>(edges.edge_halfedges.size()),
                             static_cast<int>(end - begin)});
      for (size_t i = begin; i < end; ++i) {
        edges.halfedge_edge[upward[i].second] = edge;
        edges.edge_halfedges.push_back(upward[i].second);
      }
    });
  }
  return edges;
}

std::vector<int> halfedges_on_edge(const Mesh& mesh, const MeshTopology& topology, int h) {
  const int opposite = topology.opposite[h];
  if (opposite == kBoundary) return {h};
  if (opposite >= 0) return {std::min(h, opposite), std::max(h, opposite)};
  const int source = topology.halfedge_source(mesh, h);
  const int target = topology.halfedge_target(mesh, h);
  std::vector<int> on_edge;
  for (int i = topology.faces_of_vertex_begin(source); i < topology.faces_of_vertex_end(source);
       ++i) {
    const int face = topology.vertex_faces[i];
    for (int g = 3 * face; g < 3 * face + 3; ++g) {
      const int a = topology.halfedge_source(mesh, g), b = topology.halfedge_target(mesh, g);
      if ((a == source && b == target) || (a == target && b == source)) on_edge.push_back(g);
    }
  }
  return on_edge;
}

bool is_first_halfedge_of_edge(const Mesh& mesh, const MeshTopology& topology, int h) {
  const int opposite = topology.opposite[h];
  if (opposite == kBoundary) return true;
  if (opposite >= 0) return h < opposite;
  return halfedges_on_edge(mesh, topology, h).front() == h;
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
