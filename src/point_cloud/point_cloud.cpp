// Meshing point clouds: PCL's normal estimation and greedy projection are in the module of
// point_cloud/greedy_projection.h, built when RANGEFILL_WITH_PCL is.
#include "rangefill/point_cloud/point_cloud.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>
#include <set>
#include <unordered_map>

#include "core/module_loader.h"
#include "core/nearest_points.h"
#include "point_cloud/greedy_projection.h"
#include "rangefill/core/errors.h"
#include "rangefill/core/topology.h"

namespace rangefill {

Mesher mesher_from_name(const std::string& name) {
  if (name == "none") return Mesher::none;
  if (name == "greedy") return Mesher::greedy;
  throw InvalidInput("unknown mesher '" + name + "' (known: greedy, none)");
}

std::string mesher_name(Mesher mesher) {
  return mesher == Mesher::greedy ? "greedy" : "none";
}

namespace {

// Rounds of orienting and dropping faces in make_oriented_manifold; a few suffice in practice.
constexpr int kCleaningRounds = 16;
// Two faces on an edge whose normals make more than 120° are folded onto each other.
constexpr double kFoldCosine = -0.5;

// The greedy projection's entry in its module (point_cloud/greedy_projection.h), loaded on the
// first call from beside this library.
greedy_projection::Entry greedy_projection_entry() {
  if (!RANGEFILL_WITH_PCL) {
    throw ProcessingError(
        "meshing: this rangefill was built without PCL, which meshes point clouds (configure with "
        "-DRANGEFILL_WITH_PCL=ON and libpcl-dev installed)");
  }
  static const auto entry = reinterpret_cast<greedy_projection::Entry>(
      module_entry(greedy_projection::kModule, greedy_projection::kEntry,
                   reinterpret_cast<const void*>(&mesh_point_cloud), "meshing"));
  return entry;
}

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

// In order, the triangles that have area, repeat no earlier one and put no third face on an edge.
std::vector<Triangle> edge_manifold(const std::vector<Vec3>& positions,
                                    const std::vector<Triangle>& triangles) {
  std::unordered_map<std::uint64_t, int> faces_on_edge;
  std::set<Triangle> seen;  // corners sorted
  std::vector<Triangle> kept;
  for (const Triangle& t : triangles) {
    const Vec3 cross = (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
    if (!(cross.squaredNorm() > 0)) continue;
    Triangle sorted = t;
    std::sort(sorted.begin(), sorted.end());
    bool full = false;
    for (int k = 0; k < 3; ++k) {
      const auto found = faces_on_edge.find(edge_key(t[k], t[(k + 1) % 3]));
      full |= found != faces_on_edge.end() && found->second >= 2;
    }
    if (full || !seen.insert(sorted).second) continue;
    for (int k = 0; k < 3; ++k) ++faces_on_edge[edge_key(t[k], t[(k + 1) % 3])];
    kept.push_back(t);
  }
  return kept;
}

// Orients each edge-connected piece consistently (breadth first from its first face), then turns
// it so that its face normals agree with the point normals on the whole.
void orient(const std::vector<Vec3>& positions, const std::vector<Vec3>& normals,
            std::vector<Triangle>& triangles) {
  const Mesh mesh = make_mesh(positions, triangles);
  const MeshEdges edges = build_edges(mesh, build_topology(mesh));
  auto has_directed = [&](const Triangle& t, int a, int b) {
    for (int k = 0; k < 3; ++k) {
      if (t[k] == a && t[(k + 1) % 3] == b) return true;
    }
    return false;
  };
  std::vector<char> visited(triangles.size(), 0);
  for (int start = 0; start < static_cast<int>(triangles.size()); ++start) {
    if (visited[start]) continue;
    std::vector<int> piece{start};
    visited[start] = 1;
    for (size_t i = 0; i < piece.size(); ++i) {
      const int f = piece[i];
      for (int k = 0; k < 3; ++k) {
        // Half-edge 3f + k is of f as it was; a → b is that edge the way f runs now.
        const Edge& edge = edges.edges[edges.halfedge_edge[3 * f + k]];
        const bool along = has_directed(triangles[f], edge.v0, edge.v1);
        const int a = along ? edge.v0 : edge.v1, b = along ? edge.v1 : edge.v0;
        for (int j = edge.first; j < edge.first + edge.count; ++j) {
          const int g = halfedge_face(edges.edge_halfedges[j]);
          if (visited[g]) continue;
          visited[g] = 1;
          if (has_directed(triangles[g], a, b)) std::swap(triangles[g][1], triangles[g][2]);
          piece.push_back(g);
        }
      }
    }
    double agreement = 0;
    for (int f : piece) {
      const Triangle& t = triangles[f];
      const Vec3 cross =
          (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
      for (int v : t) {
        if (normals[v].allFinite()) agreement += cross.dot(normals[v]);
      }
    }
    if (agreement < 0) {
      for (int f : piece) std::swap(triangles[f][1], triangles[f][2]);
    }
  }
}

// The faces around pinched vertex v (whose faces form several fans) that are not in its largest
// fan (the first of the largest).
std::vector<int> smaller_fans(const Mesh& mesh, const MeshTopology& topology, int v) {
  const std::vector<int> faces = faces_of_vertex(topology, v);
  std::vector<int> fan(faces.size());
  std::iota(fan.begin(), fan.end(), 0);
  std::function<int(int)> root = [&](int i) { return fan[i] == i ? i : fan[i] = root(fan[i]); };
  std::unordered_map<int, int> first_with;  // other corner w of an edge (v, w) -> a face index
  for (size_t i = 0; i < faces.size(); ++i) {
    for (int w : mesh.triangles[faces[i]]) {
      if (w == v) continue;
      const auto [found, inserted] = first_with.emplace(w, static_cast<int>(i));
      if (!inserted) fan[root(static_cast<int>(i))] = root(found->second);
    }
  }
  std::vector<int> size(faces.size(), 0);
  for (size_t i = 0; i < faces.size(); ++i) ++size[root(static_cast<int>(i))];
  const int largest = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
  std::vector<int> others;
  for (size_t i = 0; i < faces.size(); ++i) {
    if (root(static_cast<int>(i)) != largest) others.push_back(faces[i]);
  }
  return others;
}

// Orients the triangles and drops, until none is left, those that keep them from being an oriented
// manifold: both faces of an edge they traverse the same way (a twisted band) or fold across (more
// than 120° between their normals), faces folded over their neighbours (facing against the normals
// of their corners), and the smaller fans of pinched vertices.
void make_oriented_manifold(const std::vector<Vec3>& positions, const std::vector<Vec3>& normals,
                            std::vector<Triangle>& triangles) {
  for (int round = 0; round < kCleaningRounds; ++round) {
    orient(positions, normals, triangles);
    const Mesh mesh = make_mesh(positions, triangles);
    const MeshTopology topology = build_topology(mesh);
    const MeshEdges edges = build_edges(mesh, topology);
    std::vector<char> drop(triangles.size(), 0);
    for (const Edge& edge : edges.edges) {
      if (edge.count != 2) continue;
      const int h0 = edges.edge_halfedges[edge.first];
      const int h1 = edges.edge_halfedges[edge.first + 1];
      const int f0 = halfedge_face(h0), f1 = halfedge_face(h1);
      const bool twisted = topology.halfedge_source(mesh, h0) == topology.halfedge_source(mesh, h1);
      const bool folded = triangle_cross(mesh, f0).normalized().dot(
                              triangle_cross(mesh, f1).normalized()) < kFoldCosine;
      if (twisted || folded) drop[f0] = drop[f1] = 1;
    }
    const std::vector<Vec3> corner_normals = vertex_normals_from_faces(mesh);
    for (int f = 0; f < mesh.face_count(); ++f) {
      Vec3 around = Vec3::Zero();
      for (int v : mesh.triangles[f]) around += corner_normals[v];
      if (!(triangle_cross(mesh, f).dot(around) > 0)) drop[f] = 1;
    }
    for (int v : topology.nonmanifold_vertices) {
      for (int f : smaller_fans(mesh, topology, v)) drop[f] = 1;
    }
    if (std::count(drop.begin(), drop.end(), 1) == 0) return;
    std::vector<Triangle> kept;
    for (size_t f = 0; f < triangles.size(); ++f) {
      if (!drop[f]) kept.push_back(triangles[f]);
    }
    triangles = std::move(kept);
  }
}

}  // namespace

double mean_point_spacing(const std::vector<Vec3>& points) {
  if (points.size() < 2) return 0;
  const NearestPoints tree(points);
  double sum = 0;
  std::vector<int> indices;
  std::vector<double> squared;
  for (const Vec3& p : points) {
    tree.nearest(p, 2, indices, squared);
    // The nearest is the point itself, unless it has a duplicate, which is as near.
    sum += std::sqrt(squared.back());
  }
  return sum / static_cast<double>(points.size());
}

Mesh mesh_point_cloud(const Mesh& cloud, const GreedyMeshingOptions& options) {
  if (!cloud.triangles.empty()) throw InvalidInput("meshing: the point cloud already has faces");
  if (cloud.vertex_count() < 3) throw InvalidInput("meshing: fewer than three points");
  if (!(options.search_radius > 0 && options.mu > 0 && options.max_neighbours >= 3 &&
        options.max_surface_angle > 0 && options.min_angle >= 0 &&
        options.max_angle > options.min_angle && options.normal_neighbours >= 3)) {
    throw InvalidInput("meshing: greedy projection options out of range");
  }
  const double spacing = mean_point_spacing(cloud.positions);
  if (!(spacing > 0)) throw ProcessingError("meshing: every point is at the same place");
  std::vector<Vec3> normals = cloud.has_normals() ? cloud.normals : std::vector<Vec3>();
  std::vector<Triangle> triangles;
  greedy_projection_entry()(cloud.positions, normals, spacing, options, triangles);

  Mesh mesh = cloud;
  mesh.triangles = edge_manifold(cloud.positions, triangles);
  if (mesh.triangles.empty()) throw ProcessingError("meshing: the greedy projection made no face");
  make_oriented_manifold(cloud.positions, normals, mesh.triangles);
  if (mesh.triangles.empty()) throw ProcessingError("meshing: no face survived the clean-up");
  mesh.face_hole.assign(mesh.triangles.size(), kOriginal);
  for (ExtraProperty& property : mesh.face_properties) {
    property.values.assign(mesh.triangles.size(), 0);  // declared by the file for no face
  }
  return mesh;
}

}  // namespace rangefill
