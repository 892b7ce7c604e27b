#include "rangefill/eval/punch.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <queue>
#include <random>
#include <unordered_map>

#include "rangefill/core/errors.h"
#include "rangefill/core/topology.h"
#include "rangefill/eval/curvature.h"

namespace rangefill {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Uniform in [0, 1) from 53 random bits: the same on every standard library.
double uniform01(std::mt19937_64& random) {
  return (random() >> 11) * 0x1.0p-53;
}

// The mesh's edges as adjacency lists (CSR).
struct EdgeGraph {
  std::vector<int> offsets, neighbours;
};

EdgeGraph edge_graph(const Mesh& mesh, const MeshEdges& edges) {
  EdgeGraph graph;
  graph.offsets.assign(mesh.vertex_count() + 1, 0);
  for (const Edge& edge : edges.edges) {
    ++graph.offsets[edge.v0 + 1];
    ++graph.offsets[edge.v1 + 1];
  }
  std::partial_sum(graph.offsets.begin(), graph.offsets.end(), graph.offsets.begin());
  graph.neighbours.resize(graph.offsets.back());
  std::vector<int> cursor(graph.offsets.begin(), graph.offsets.end() - 1);
  for (const Edge& edge : edges.edges) {
    graph.neighbours[cursor[edge.v0]++] = edge.v1;
    graph.neighbours[cursor[edge.v1]++] = edge.v0;
  }
  return graph;
}

// Dijkstra distances along edges from the nearest of `sources`, for vertices closer than `limit`;
// `previous`, when given, receives the vertex each was reached from.
std::unordered_map<int, double> distances_within(const Mesh& mesh, const EdgeGraph& graph,
                                                 const std::vector<int>& sources, double limit,
                                                 std::unordered_map<int, int>* previous = nullptr) {
  std::unordered_map<int, double> distance;
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int source : sources) {
    distance[source] = 0.0;
    queue.emplace(0.0, source);
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance.at(v)) continue;
    for (int i = graph.offsets[v]; i < graph.offsets[v + 1]; ++i) {
      const int w = graph.neighbours[i];
      const double through = d + (mesh.positions[v] - mesh.positions[w]).norm();
      if (through >= limit) continue;
      const auto found = distance.find(w);
      if (found == distance.end() || through < found->second) {
        distance[w] = through;
        if (previous) (*previous)[w] = v;
        queue.emplace(through, w);
      }
    }
  }
  return distance;
}

// The region is a topological disk whose border is one loop through distinct vertices.
bool is_simple_disk(const Mesh& mesh, const std::vector<int>& faces) {
  std::map<std::pair<int, int>, int> edge_faces;
  std::map<int, int> vertex_index;
  for (int face : faces) {
    const Triangle& t = mesh.triangles[face];
    for (int k = 0; k < 3; ++k) {
      vertex_index.emplace(t[k], static_cast<int>(vertex_index.size()));
      ++edge_faces[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
    }
  }
  const long long euler = static_cast<long long>(vertex_index.size()) -
                          static_cast<long long>(edge_faces.size()) +
                          static_cast<long long>(faces.size());
  if (euler != 1) return false;
  // Border: every border vertex on exactly two border edges, all in one cycle.
  std::map<int, std::vector<int>> border;
  for (const auto& [edge, count] : edge_faces) {
    if (count != 1) continue;
    border[edge.first].push_back(edge.second);
    border[edge.second].push_back(edge.first);
  }
  if (border.empty()) return false;
  for (const auto& [v, next] : border) {
    if (next.size() != 2) return false;
  }
  size_t length = 0;
  int previous = -1, current = border.begin()->first;
  do {
    const std::vector<int>& next = border.at(current);
    const int step = next[0] != previous ? next[0] : next[1];
    previous = current;
    current = step;
    ++length;
  } while (current != border.begin()->first && length <= border.size());
  // Connected faces follow from one border cycle plus Euler characteristic 1 (a disk).
  return length == border.size();
}

// The faces around the vertices closer than `radius` whose three vertices all are, ascending.
std::vector<int> faces_within(const Mesh& mesh, const MeshTopology& topology,
                              const std::unordered_map<int, double>& distance, double radius) {
  std::vector<int> region;
  for (const auto& [v, d] : distance) {
    if (d >= radius) continue;
    for_each_face_of_vertex(topology, v, [&](int face) {
      const Triangle& t = mesh.triangles[face];
      const bool inside = std::all_of(t.begin(), t.end(), [&](int w) {
        const auto found = distance.find(w);
        return found != distance.end() && found->second < radius;
      });
      if (inside) region.push_back(face);
    });
  }
  std::sort(region.begin(), region.end());
  region.erase(std::unique(region.begin(), region.end()), region.end());
  return region;
}

double area_of(const Mesh& mesh, const std::vector<int>& faces) {
  double area = 0;
  for (int face : faces) area += 0.5 * triangle_cross(mesh, face).norm();
  return area;
}

// What a region is classified by: the curvature of every vertex and the dihedral angle of every
// edge of the input, computed once.
struct SurfaceShape {
  const Mesh& mesh;
  const MeshTopology& topology;
  const MeshEdges& edges;
  VertexCurvature curvature;
  std::vector<double> dihedral;
};

// Sets the hole's area, bending, curvature class and sharp-feature flag from its removed faces.
void classify(const SurfaceShape& surface, const PunchOptions& options, double mean_edge,
              PunchedHole& hole) {
  const std::vector<int>& faces = hole.removed_faces;
  hole.area = area_of(surface.mesh, faces);
  std::vector<int> vertices;
  for (int face : faces) {
    for (int v : surface.mesh.triangles[face]) vertices.push_back(v);
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  double weighted = 0, weight = 0;
  for (int v : vertices) {
    weighted += surface.curvature.area[v] * surface.curvature.max_principal(v);
    weight += surface.curvature.area[v];
  }
  hole.bending = weight > 0 ? weighted / weight * std::sqrt(hole.area / kPi) : 0;
  hole.curvature = hole.bending < options.low_bending    ? CurvatureClass::low
                   : hole.bending < options.high_bending ? CurvatureClass::medium
                                                         : CurvatureClass::high;
  // Sharp edges between two faces of the region (each edge once, from its lower half-edge).
  const double sharp = options.sharp_angle * kPi / 180;
  double sharp_length = 0;
  for (int face : faces) {
    for (int h = 3 * face; h < 3 * face + 3; ++h) {
      const int opposite = surface.topology.opposite[h];
      if (opposite < h || !std::binary_search(faces.begin(), faces.end(), opposite / 3)) continue;
      const int edge_index = surface.edges.halfedge_edge[h];
      if (surface.dihedral[edge_index] < sharp) continue;
      const Edge& edge = surface.edges.edges[edge_index];
      sharp_length += (surface.mesh.positions[edge.v0] - surface.mesh.positions[edge.v1]).norm();
    }
  }
  hole.sharp_feature = sharp_length >= options.sharp_length * mean_edge;
}

// Whether the hole is of kind `kind` of (low, medium, high curvature, sharp feature).
bool of_kind(const PunchedHole& hole, int kind) {
  return kind == 3 ? hole.sharp_feature : static_cast<int>(hole.curvature) == kind;
}

void check_options(const PunchOptions& options) {
  if (!(options.min_radius > 0 && options.max_radius >= options.min_radius)) {
    throw InvalidInput("punch: radii must satisfy 0 < min_radius <= max_radius");
  }
  if (options.shapes.empty()) throw InvalidInput("punch: no hole shape given");
  if (!(options.min_aspect > 0 && options.max_aspect >= options.min_aspect &&
        options.max_aspect <= 1)) {
    throw InvalidInput("punch: aspects must satisfy 0 < min_aspect <= max_aspect <= 1");
  }
  if (!(options.low_bending >= 0 && options.high_bending >= options.low_bending)) {
    throw InvalidInput("punch: bending thresholds must satisfy 0 <= low <= high");
  }
  if (!(options.separation >= 0 && options.sharp_angle >= 0 && options.sharp_length >= 0)) {
    throw InvalidInput("punch: separation, sharp angle and sharp length must not be negative");
  }
}

}  // namespace

std::uint64_t seed_for_mesh(std::uint64_t seed, const std::string& name) {
  std::uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : name) hash = (hash ^ c) * 1099511628211ull;
  return seed ^ hash;
}

PunchResult punch_holes(const Mesh& mesh, const PunchOptions& options) {
  if (mesh.vertex_count() == 0) throw InvalidInput("punch: the mesh has no vertices");
  check_options(options);
  const MeshTopology topology = build_topology(mesh);
  const double mean_edge = mean_edge_length(mesh, topology);
  const MeshEdges edges = build_edges(mesh, topology);
  const EdgeGraph graph = edge_graph(mesh, edges);
  const SurfaceShape surface{mesh, topology, edges, vertex_curvature(mesh, topology),
                             dihedral_angles(mesh, edges)};

  std::mt19937_64 random(options.seed);
  std::vector<char> vertex_touched(mesh.vertex_count(), 0);
  std::vector<PunchedHole> holes;
  for (int hole = 0; hole < options.holes; ++hole) {
    const HoleShape shape = options.shapes[(hole + hole / 4) % options.shapes.size()];
    for (int attempt = 0; attempt < options.attempts; ++attempt) {
      PunchedHole candidate;
      candidate.shape = shape;
      candidate.centre =
          static_cast<int>(random() % static_cast<std::uint64_t>(mesh.vertex_count()));
      const double size =
          (options.min_radius + (options.max_radius - options.min_radius) * uniform01(random)) *
          mean_edge;
      candidate.radius = size;
      std::vector<int> path = {candidate.centre};
      if (shape == HoleShape::elongated) {
        const double aspect =
            options.min_aspect + (options.max_aspect - options.min_aspect) * uniform01(random);
        candidate.radius = std::max(aspect * size, 2 * mean_edge);
        const double length = 2 * (size - candidate.radius);
        std::unordered_map<int, int> previous;
        const auto from_start =
            distances_within(mesh, graph, path, std::max(length, 0.0), &previous);
        std::vector<int> ends;  // vertices at 80–100 % of the length
        for (const auto& [v, d] : from_start) {
          if (d >= 0.8 * length) ends.push_back(v);
        }
        if (ends.empty()) continue;
        std::sort(ends.begin(), ends.end());
        const int end = ends[random() % ends.size()];
        candidate.length = from_start.at(end);
        for (int v = end; v != candidate.centre; v = previous.at(v)) path.push_back(v);
        candidate.centre = path[path.size() / 2];
      }
      const auto distance =
          distances_within(mesh, graph, path, candidate.radius + options.separation * mean_edge);
      const bool near_other_hole =
          std::any_of(distance.begin(), distance.end(),
                      [&](const auto& entry) { return vertex_touched[entry.first] != 0; });
      candidate.removed_faces = faces_within(mesh, topology, distance, candidate.radius);
      if (near_other_hole || candidate.removed_faces.empty()) continue;
      if (!is_simple_disk(mesh, candidate.removed_faces)) continue;
      classify(surface, options, mean_edge, candidate);
      if (options.spread && attempt < options.attempts / 2 && !of_kind(candidate, hole % 4)) {
        continue;
      }
      for (int face : candidate.removed_faces) {
        for (int v : mesh.triangles[face]) vertex_touched[v] = 1;
      }
      holes.push_back(std::move(candidate));
      break;
    }
  }
  return remove_holes(mesh, std::move(holes));
}

PunchResult remove_holes(const Mesh& mesh, std::vector<PunchedHole> holes) {
  std::vector<char> face_removed(mesh.face_count(), 0);
  for (PunchedHole& hole : holes) {
    std::sort(hole.removed_faces.begin(), hole.removed_faces.end());
    for (int face : hole.removed_faces) {
      if (face < 0 || face >= mesh.face_count() || face_removed[face]) {
        throw InvalidInput("punch: face " + std::to_string(face) +
                           " is out of range or in two holes");
      }
      face_removed[face] = 1;
    }
    hole.area = area_of(mesh, hole.removed_faces);
  }
  PunchResult result;
  result.holes = std::move(holes);
  std::vector<int> kept_faces;
  for (int f = 0; f < mesh.face_count(); ++f) {
    if (!face_removed[f]) kept_faces.push_back(f);
  }
  // Keep the vertices still used, in their input order.
  std::vector<char> used(mesh.vertex_count(), 0);
  for (int face : kept_faces) {
    for (int v : mesh.triangles[face]) used[v] = 1;
  }
  std::vector<int> new_index(mesh.vertex_count(), -1);
  std::vector<Vec3> positions;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (!used[v]) continue;
    new_index[v] = static_cast<int>(positions.size());
    positions.push_back(mesh.positions[v]);
    result.original_vertex.push_back(v);
  }
  std::vector<Triangle> triangles;
  for (int face : kept_faces) {
    const Triangle& t = mesh.triangles[face];
    triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
  }
  result.mesh = make_mesh(std::move(positions), std::move(triangles));
  result.mesh.storage = mesh.storage;
  return result;
}

std::string shape_name(HoleShape shape) {
  return shape == HoleShape::disk ? "disk" : "elongated";
}

HoleShape shape_from_name(const std::string& name) {
  if (name == "disk") return HoleShape::disk;
  if (name == "elongated") return HoleShape::elongated;
  throw InvalidInput("punch: unknown hole shape '" + name + "' (expected disk or elongated)");
}

std::string curvature_name(CurvatureClass curvature) {
  switch (curvature) {
    case CurvatureClass::low:
      return "low";
    case CurvatureClass::medium:
      return "medium";
    case CurvatureClass::high:
      break;
  }
  return "high";
}

CurvatureClass curvature_from_name(const std::string& name) {
  for (CurvatureClass c : {CurvatureClass::low, CurvatureClass::medium, CurvatureClass::high}) {
    if (curvature_name(c) == name) return c;
  }
  throw InvalidInput("punch: unknown curvature class '" + name +
                     "' (expected low, medium or high)");
}

}  // namespace rangefill
