#include "rangefill/core/topology.h"

#include <algorithm>
#include <numeric>
#include <optional>
#include <set>

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

constexpr auto halfedge_source = &MeshTopology::halfedge_source;
constexpr auto halfedge_target = &MeshTopology::halfedge_target;

// The half-edges of each edge grouped at the edge's lower end: chained from head[v] through
// next[h], -1 ending a chain. A vertex's chain holds every half-edge of its upward edges.
struct UpwardChains {
  std::vector<int> head;  // per vertex
  std::vector<int> next;  // per half-edge
};

UpwardChains upward_chains(const Mesh& mesh) {
  UpwardChains chains{std::vector<int>(mesh.vertex_count(), -1),
                      std::vector<int>(3 * static_cast<size_t>(mesh.face_count()))};
  for (int h = static_cast<int>(chains.next.size()) - 1; h >= 0; --h) {
    const int lower = std::min(halfedge_source(mesh, h), halfedge_target(mesh, h));
    chains.next[h] = chains.head[lower];
    chains.head[lower] = h;
  }
  return chains;
}

// The half-edges of the edges whose lower end is v (its chain from head[v] through next), as
// (higher end, half-edge), sorted: each run of one higher end is an edge, its half-edges
// ascending.
void upward_halfedges(const Mesh& mesh, const std::vector<int>& head, const std::vector<int>& next,
                      int v, std::vector<std::pair<int, int>>& upward) {
  upward.clear();
  for (int h = head[v]; h >= 0; h = next[h]) {
    upward.emplace_back(std::max(halfedge_source(mesh, h), halfedge_target(mesh, h)), h);
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
EdgeCounts pair_opposites_of_range(const Mesh& mesh, const std::vector<int>& head,
                                   MeshTopology& topology, int first_vertex, int last_vertex) {
  EdgeCounts counts;
  std::vector<std::pair<int, int>> upward;
  for (int v = first_vertex; v < last_vertex; ++v) {
    upward_halfedges(mesh, head, topology.opposite, v, upward);
    for (const auto& [higher, h] : upward) topology.opposite[h] = kBoundary;
    for_each_edge_run(upward, [&](size_t begin, size_t end) {
      ++counts.edges;
      counts.duplicated_faces += duplicated_faces(mesh, upward, begin, end);
      if (end - begin == 2) {
        const int a = upward[begin].second, b = upward[begin + 1].second;
        if (halfedge_source(mesh, a) == halfedge_target(mesh, b)) {
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
// half-edges of its own edges (the same at any thread count). The opposites overwrite the chains'
// links (no second array of the half-edges' size), each vertex's once its chain is read.
void pair_opposites(const Mesh& mesh, MeshTopology& topology) {
  UpwardChains chains = upward_chains(mesh);
  topology.opposite = std::move(chains.next);
  const int vertices = mesh.vertex_count();
  std::vector<EdgeCounts> ranges(kMeshRanges);
  parallel_for(kMeshRanges, mesh_pass_threads(mesh.face_count()), [&](int r) {
    ranges[r] = pair_opposites_of_range(mesh, chains.head, topology, range_begin(vertices, r),
                                        range_begin(vertices, r + 1));
  });
  for (const EdgeCounts& range : ranges) {
    topology.edge_count += range.edges;
    topology.nonmanifold_edge_count += range.nonmanifold_edges;
    topology.misoriented_edge_count += range.misoriented_edges;
    topology.duplicated_face_count += range.duplicated_faces;
  }
}

// The half-edge leaving v in `face`.
int halfedge_leaving(const Mesh& mesh, int face, int v) {
  int h = 3 * face;
  while (halfedge_source(mesh, h) != v) ++h;
  return h;
}

// The half-edges on h's edge among the faces [first, last), ascending when they are (they must
// hold every face on the edge: those of one of its ends).
std::vector<int> halfedges_on_edge_among(const Mesh& mesh, int h, const int* first,
                                         const int* last) {
  const int source = halfedge_source(mesh, h), target = halfedge_target(mesh, h);
  std::vector<int> on_edge;
  for (const int* face = first; face != last; ++face) {
    for (int g = 3 * *face; g < 3 * *face + 3; ++g) {
      const int a = halfedge_source(mesh, g), b = halfedge_target(mesh, g);
      if ((a == source && b == target) || (a == target && b == source)) on_edge.push_back(g);
    }
  }
  return on_edge;
}

// The fans of faces around vertex v, its faces [first, last) (ascending): its faces linked through
// the two-face edges at v. `parent` is scratch space.
int count_fans(const Mesh& mesh, const MeshTopology& topology, int v, const int* first,
               const int* last, std::vector<int>& parent) {
  const int degree = static_cast<int>(last - first);
  parent.resize(degree);
  std::iota(parent.begin(), parent.end(), 0);
  int fans = degree;
  for (int i = 0; i < degree; ++i) {
    const int h = halfedge_leaving(mesh, first[i], v);
    // The two edges of the face at v are the one leaving v and the one entering it.
    for (int at_v : {h, prev_halfedge(h)}) {
      int across = topology.opposite[at_v];
      if (across == kNonManifold) {  // linked too when its edge has two misoriented faces
        const std::vector<int> on_edge = halfedges_on_edge_among(mesh, at_v, first, last);
        across = on_edge.size() == 2 ? on_edge[on_edge[0] == at_v] : kBoundary;
      }
      if (across < 0) continue;
      const int a = find_root(parent, i);
      const int b = find_root(
          parent, static_cast<int>(std::lower_bound(first, last, halfedge_face(across)) - first));
      if (a != b) {
        parent[a] = b;
        --fans;
      }
    }
  }
  return fans;
}

// Where the walk round each vertex starts (its half-edge leaving it in its lowest face), and the
// vertices no walk serves, their faces listed; those of several fans (a pinch, or faces meeting
// at a non-manifold edge) are non-manifold. The walks in ranges of vertices in parallel.
void find_vertex_walks(const Mesh& mesh, MeshTopology& topology) {
  const int vertices = mesh.vertex_count();
  topology.vertex_halfedge.assign(vertices, kNoFaces);
  std::vector<int> degree(vertices, 0);
  for (int h = 0; h < static_cast<int>(topology.opposite.size()); ++h) {
    const int v = halfedge_source(mesh, h);
    if (degree[v]++ == 0) topology.vertex_halfedge[v] = h;
  }
  std::vector<std::vector<int>> unwalked(kMeshRanges);
  parallel_for(kMeshRanges, mesh_pass_threads(mesh.face_count()), [&](int r) {
    for (int v = range_begin(vertices, r); v < range_begin(vertices, r + 1); ++v) {
      if (degree[v] == 0) continue;
      int reached = 0;
      for_each_face_of_fan(topology, topology.vertex_halfedge[v], [&](int) { ++reached; });
      // Distinct faces: a walk visits each half-edge leaving v once, each face has one.
      if (reached != degree[v]) unwalked[r].push_back(v);
    }
  });
  topology.listed_face_offsets.push_back(0);
  for (const std::vector<int>& range : unwalked) {
    for (int v : range) {
      topology.vertex_halfedge[v] = kListedFaces;
      topology.listed_vertices.push_back(v);
      topology.listed_face_offsets.push_back(topology.listed_face_offsets.back() + degree[v]);
    }
  }
  topology.listed_faces.resize(topology.listed_face_offsets.back());
  std::vector<int> cursor(topology.listed_face_offsets.begin(),
                          topology.listed_face_offsets.end() - 1);
  const auto& listed = topology.listed_vertices;
  for (int f = 0; f < mesh.face_count(); ++f) {
    for (int v : mesh.triangles[f]) {
      if (topology.vertex_halfedge[v] != kListedFaces) continue;
      topology.listed_faces[cursor[std::lower_bound(listed.begin(), listed.end(), v) -
                                   listed.begin()]++] = f;
    }
  }
  std::vector<int> parent;
  for (size_t i = 0; i < listed.size(); ++i) {
    const int* first = topology.listed_faces.data() + topology.listed_face_offsets[i];
    const int* last = topology.listed_faces.data() + topology.listed_face_offsets[i + 1];
    if (count_fans(mesh, topology, listed[i], first, last, parent) > 1) {
      topology.nonmanifold_vertices.push_back(listed[i]);
    }
  }
}

}  // namespace

MeshTopology build_topology(const Mesh& mesh) {
  MeshTopology topology;
  pair_opposites(mesh, topology);
  find_vertex_walks(mesh, topology);
  return topology;
}

std::vector<int> faces_of_vertex(const MeshTopology& topology, int v) {
  std::vector<int> faces;
  for_each_face_of_vertex(topology, v, [&](int face) { faces.push_back(face); });
  std::sort(faces.begin(), faces.end());
  return faces;
}

FaceComponents face_components(const Mesh& mesh, const MeshTopology& topology) {
  // Union-find whose roots are the components' lowest faces (parent[f] <= f), so that one array
  // serves: in face order, a face's parent already holds its component.
  std::vector<int> parent(mesh.face_count());
  std::iota(parent.begin(), parent.end(), 0);
  for (int h = 0; h < static_cast<int>(topology.opposite.size()); ++h) {
    const auto join = [&](int other) {
      const int a = find_root(parent, halfedge_face(other));
      const int b = find_root(parent, halfedge_face(h));
      parent[std::max(a, b)] = std::min(a, b);
    };
    const int opposite = topology.opposite[h];
    if (opposite > h) join(opposite);
    if (opposite == kNonManifold) {
      for (int other : halfedges_on_edge(mesh, topology, h)) join(other);
    }
  }
  FaceComponents components;  // numbered in the order of their first faces
  for (int f = 0; f < mesh.face_count(); ++f) {
    parent[f] = parent[f] == f ? components.count++ : parent[parent[f]];
  }
  components.of_face = std::move(parent);
  return components;
}

MeshEdges build_edges(const Mesh& mesh, const MeshTopology& topology) {
  MeshEdges edges;
  edges.edges.reserve(topology.edge_count);
  edges.edge_halfedges.reserve(topology.opposite.size());
  edges.halfedge_edge.assign(topology.opposite.size(), -1);
  const UpwardChains chains = upward_chains(mesh);
  std::vector<std::pair<int, int>> upward;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    upward_halfedges(mesh, chains.head, chains.next, v, upward);
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
  const std::vector<int> faces = faces_of_vertex(topology, halfedge_source(mesh, h));
  return halfedges_on_edge_among(mesh, h, faces.data(), faces.data() + faces.size());
}

bool is_first_halfedge_of_edge(const Mesh& mesh, const MeshTopology& topology, int h) {
  const int opposite = topology.opposite[h];
  if (opposite == kBoundary) return true;
  if (opposite >= 0) return h < opposite;
  return halfedges_on_edge(mesh, topology, h).front() == h;
}

Vec3 vertex_normal(const Mesh& mesh, const MeshTopology& topology, int v) {
  Vec3 normal = Vec3::Zero();  // summed in face order, as vertex_normals_from_faces does
  for (int face : faces_of_vertex(topology, v)) normal += triangle_cross(mesh, face);
  const double length = normal.norm();
  if (length > 0) normal /= length;
  return normal;
}

int find_halfedge(const Mesh& mesh, const MeshTopology& topology, int from, int to) {
  int first = -1;
  for_each_face_of_vertex(topology, from, [&](int face) {
    const int h = halfedge_leaving(mesh, face, from);
    if (halfedge_target(mesh, h) == to && (first < 0 || h < first)) first = h;
  });
  return first;
}

bool has_edge(const Mesh& mesh, const MeshTopology& topology, int a, int b) {
  return find_halfedge(mesh, topology, a, b) >= 0 || find_halfedge(mesh, topology, b, a) >= 0;
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
  std::optional<FaceComponents> components;  // when first asked
  for (int v : topology.nonmanifold_vertices) {
    if (unfillable[v]) continue;
    if (!components) components = face_components(mesh, topology);
    const std::vector<int> faces = faces_of_vertex(topology, v);
    int leaving_boundary = 0;
    bool one_component = true;
    for (int face : faces) {
      one_component =
          one_component && components->of_face[face] == components->of_face[faces.front()];
      leaving_boundary += topology.opposite[halfedge_leaving(mesh, face, v)] == kBoundary;
    }
    unfillable[v] =
        !one_component || leaving_boundary != count_fans(mesh, topology, v, faces.data(),
                                                         faces.data() + faces.size(), parent);
  }
  std::vector<int> vertices;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (unfillable[v]) vertices.push_back(v);
  }
  return vertices;
}

std::vector<int> faces_within_rings(const Mesh& mesh, const MeshTopology& topology,
                                    const std::vector<int>& vertices, int rings) {
  std::set<int> front(vertices.begin(), vertices.end()), faces;
  for (int ring = 0; ring < rings; ++ring) {
    std::set<int> reached;
    for (int v : front) {
      for_each_face_of_vertex(topology, v, [&](int face) {
        if (faces.insert(face).second) {
          for (int corner : mesh.triangles[face]) reached.insert(corner);
        }
      });
    }
    front = std::move(reached);
  }
  return {faces.begin(), faces.end()};
}

}  // namespace rangefill
