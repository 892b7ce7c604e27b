#include "rangefill/punch.h"

#include <algorithm>
#include <map>
#include <queue>
#include <random>
#include <unordered_map>

#include "rangefill/errors.h"
#include "rangefill/topology.h"

namespace rangefill {

namespace {

// Uniform in [0, 1) from 53 random bits: the same on every standard library.
double uniform01(std::mt19937_64& random) {
  return (random() >> 11) * 0x1.0p-53;
}

// Dijkstra distances along edges from `source`, for vertices closer than `limit`.
std::unordered_map<int, double> distances_within(const Mesh& mesh, const std::vector<int>& offsets,
                                                 const std::vector<int>& neighbours, int source,
                                                 double limit) {
  std::unordered_map<int, double> distance{{source, 0.0}};
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  queue.emplace(0.0, source);
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance.at(v)) continue;
    for (int i = offsets[v]; i < offsets[v + 1]; ++i) {
      const int w = neighbours[i];
      const double through = d + (mesh.positions[v] - mesh.positions[w]).norm();
      if (through >= limit) continue;
      const auto found = distance.find(w);
      if (found == distance.end() || through < found->second) {
        distance[w] = through;
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

}  // namespace

std::uint64_t seed_for_mesh(std::uint64_t seed, const std::string& name) {
  std::uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : name) hash = (hash ^ c) * 1099511628211ull;
  return seed ^ hash;
}

Mesh extract_faces(const Mesh& mesh, const std::vector<int>& faces) {
  std::vector<int> new_index(mesh.vertex_count(), -1);
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  for (int face : faces) {
    Triangle t;
    for (int k = 0; k < 3; ++k) {
      int& index = new_index[mesh.triangles[face][k]];
      if (index < 0) {
        index = static_cast<int>(positions.size());
        positions.push_back(mesh.positions[mesh.triangles[face][k]]);
      }
      t[k] = index;
    }
    triangles.push_back(t);
  }
  return make_mesh(std::move(positions), std::move(triangles));
}

PunchResult punch_holes(const Mesh& mesh, const PunchOptions& options) {
  if (mesh.vertex_count() == 0) throw InvalidInput("punch: the mesh has no vertices");
  if (!(options.min_radius > 0 && options.max_radius >= options.min_radius)) {
    throw InvalidInput("punch: radii must satisfy 0 < min_radius <= max_radius");
  }
  const MeshTopology topology = build_topology(mesh);
  const double mean_edge = mean_edge_length(mesh, topology);
  std::vector<int> offsets(mesh.vertex_count() + 1, 0), neighbours;
  for (const Edge& edge : topology.edges) {
    ++offsets[edge.v0 + 1];
    ++offsets[edge.v1 + 1];
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  neighbours.resize(offsets.back());
  {
    std::vector<int> cursor(offsets.begin(), offsets.end() - 1);
    for (const Edge& edge : topology.edges) {
      neighbours[cursor[edge.v0]++] = edge.v1;
      neighbours[cursor[edge.v1]++] = edge.v0;
    }
  }

  std::mt19937_64 random(options.seed);
  std::vector<char> face_removed(mesh.face_count(), 0), vertex_touched(mesh.vertex_count(), 0);
  PunchResult result;
  for (int hole = 0; hole < options.holes; ++hole) {
    for (int attempt = 0; attempt < options.attempts; ++attempt) {
      const int centre =
          static_cast<int>(random() % static_cast<std::uint64_t>(mesh.vertex_count()));
      const double radius =
          (options.min_radius + (options.max_radius - options.min_radius) * uniform01(random)) *
          mean_edge;
      const auto distance = distances_within(mesh, offsets, neighbours, centre,
                                             radius + options.separation * mean_edge);
      bool near_other_hole = false;
      std::vector<int> region;
      for (const auto& [v, d] : distance) {
        near_other_hole |= vertex_touched[v] != 0;
        if (d >= radius) continue;
        for (int i = topology.faces_of_vertex_begin(v); i < topology.faces_of_vertex_end(v); ++i) {
          const Triangle& t = mesh.triangles[topology.vertex_faces[i]];
          const bool inside = std::all_of(t.begin(), t.end(), [&](int w) {
            const auto found = distance.find(w);
            return found != distance.end() && found->second < radius;
          });
          if (inside) region.push_back(topology.vertex_faces[i]);
        }
      }
      if (near_other_hole || region.empty()) continue;
      std::sort(region.begin(), region.end());
      region.erase(std::unique(region.begin(), region.end()), region.end());
      if (!is_simple_disk(mesh, region)) continue;
      for (int face : region) {
        face_removed[face] = 1;
        for (int v : mesh.triangles[face]) vertex_touched[v] = 1;
      }
      result.holes.push_back({centre, radius, std::move(region)});
      break;
    }
  }

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

}  // namespace rangefill
