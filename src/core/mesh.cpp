#include "rangefill/core/mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "rangefill/core/errors.h"
#include "rangefill/core/geometry2d.h"
#include "rangefill/core/parallel.h"
#include "rangefill/core/topology.h"

namespace rangefill {

int add_vertex(Mesh& mesh, const Vec3& position, int hole, const Rgb& color, const Vec3& normal) {
  mesh.positions.push_back(position);
  if (mesh.has_colors()) mesh.colors.push_back(color);
  if (mesh.has_normals()) mesh.normals.push_back(normal);
  mesh.vertex_hole.push_back(hole);
  for (ExtraProperty& property : mesh.vertex_properties) property.values.push_back(0.0);
  return mesh.vertex_count() - 1;
}

int add_face(Mesh& mesh, const Triangle& triangle, int hole) {
  mesh.triangles.push_back(triangle);
  mesh.face_hole.push_back(hole);
  for (ExtraProperty& property : mesh.face_properties) property.values.push_back(0.0);
  return mesh.face_count() - 1;
}

void reserve_more(Mesh& mesh, int vertices, int faces) {
  const size_t vertex_total = mesh.positions.size() + vertices;
  const size_t face_total = mesh.triangles.size() + faces;
  mesh.positions.reserve(vertex_total);
  if (mesh.has_colors()) mesh.colors.reserve(vertex_total);
  if (mesh.has_normals()) mesh.normals.reserve(vertex_total);
  mesh.vertex_hole.reserve(vertex_total);
  for (ExtraProperty& property : mesh.vertex_properties) property.values.reserve(vertex_total);
  mesh.triangles.reserve(face_total);
  mesh.face_hole.reserve(face_total);
  for (ExtraProperty& property : mesh.face_properties) property.values.reserve(face_total);
}

Mesh make_mesh(std::vector<Vec3> positions, std::vector<Triangle> triangles) {
  Mesh mesh;
  mesh.positions = std::move(positions);
  mesh.triangles = std::move(triangles);
  mesh.vertex_hole.assign(mesh.positions.size(), kOriginal);
  mesh.face_hole.assign(mesh.triangles.size(), kOriginal);
  return mesh;
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

namespace {

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw InvalidInput(source + ": " + what);
}

void require(bool condition, const std::string& source, const std::string& what) {
  if (!condition) fail(source, what);
}

void validate_properties(const std::vector<ExtraProperty>& properties, size_t count,
                         const std::string& source, const char* element) {
  for (const ExtraProperty& property : properties) {
    require(property.values.size() == count, source,
            std::string(element) + " property '" + property.name + "' has " +
                std::to_string(property.values.size()) + " values for " + std::to_string(count) +
                " elements");
  }
}

}  // namespace

void validate_mesh(const Mesh& mesh, const std::string& source) {
  const size_t vertex_count = mesh.positions.size();
  const size_t face_count = mesh.triangles.size();
  require(vertex_count <= static_cast<size_t>(std::numeric_limits<int>::max()) &&
              face_count <= static_cast<size_t>(std::numeric_limits<int>::max() / 3),
          source, "too many elements for 32-bit indices");
  // Per element, the message is made only on failure, so that the loops stay cheap.
  for (size_t v = 0; v < vertex_count; ++v) {
    if (!mesh.positions[v].allFinite()) {
      fail(source, "vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
  }
  const int vertices = static_cast<int>(vertex_count);
  for (size_t f = 0; f < face_count; ++f) {
    const Triangle& t = mesh.triangles[f];
    for (int corner = 0; corner < 3; ++corner) {
      if (t[corner] < 0 || t[corner] >= vertices) {
        fail(source, "face " + std::to_string(f) + " refers to vertex " +
                         std::to_string(t[corner]) + ", out of range [0, " +
                         std::to_string(vertex_count) + ")");
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      fail(source, "face " + std::to_string(f) + " repeats a vertex (" + std::to_string(t[0]) +
                       " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + ")");
    }
  }
  require(mesh.colors.empty() || mesh.colors.size() == vertex_count, source,
          "colour count differs from vertex count");
  require(mesh.normals.empty() || mesh.normals.size() == vertex_count, source,
          "normal count differs from vertex count");
  for (size_t v = 0; v < mesh.normals.size(); ++v) {
    if (!mesh.normals[v].allFinite()) {
      fail(source, "vertex " + std::to_string(v) + " has a non-finite normal");
    }
  }
  require(mesh.vertex_hole.size() == vertex_count, source,
          "vertex provenance count differs from vertex count");
  require(mesh.face_hole.size() == face_count, source,
          "face provenance count differs from face count");
  validate_properties(mesh.vertex_properties, vertex_count, source, "vertex");
  validate_properties(mesh.face_properties, face_count, source, "face");
}

double mean_edge_length(const Mesh& mesh) {
  return mean_edge_length(mesh, build_topology(mesh));
}

double mean_edge_length(const Mesh& mesh, const MeshTopology& topology) {
  if (topology.edge_count == 0) return 0.0;
  // Sums over fixed ranges of half-edges, added in order: the same at any thread count.
  const int halfedges = static_cast<int>(topology.opposite.size());
  std::vector<double> sums(kMeshRanges, 0.0);
  parallel_for(kMeshRanges, mesh_pass_threads(halfedges), [&](int r) {
    double sum = 0.0;
    for (int h = range_begin(halfedges, r); h < range_begin(halfedges, r + 1); ++h) {
      if (!is_first_halfedge_of_edge(mesh, topology, h)) continue;
      sum += (mesh.positions[topology.halfedge_source(mesh, h)] -
              mesh.positions[topology.halfedge_target(mesh, h)])
                 .norm();
    }
    sums[r] = sum;
  });
  return std::accumulate(sums.begin(), sums.end(), 0.0) / topology.edge_count;
}

std::array<Vec3, 2> bounding_box(const Mesh& mesh) {
  if (mesh.positions.empty()) return {Vec3::Zero(), Vec3::Zero()};
  Vec3 lo = mesh.positions.front();
  Vec3 hi = lo;
  for (const Vec3& p : mesh.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

Vec3 triangle_cross(const Mesh& mesh, int face) {
  const Triangle& t = mesh.triangles[face];
  const Vec3& a = mesh.positions[t[0]];
  return (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
}

bool is_degenerate(const Mesh& mesh, int face) {
  const Triangle& t = mesh.triangles[face];
  double longest = 0;
  for (int k = 0; k < 3; ++k) {
    longest =
        std::max(longest, (mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]).squaredNorm());
  }
  // |cross| = longest edge × height.
  return !(triangle_cross(mesh, face).norm() > 1e-12 * longest);
}

std::vector<Vec3> vertex_normals_from_faces(const Mesh& mesh) {
  std::vector<Vec3> normals(mesh.positions.size(), Vec3::Zero());
  for (int f = 0; f < mesh.face_count(); ++f) {
    const Vec3 cross = triangle_cross(mesh, f);
    for (int v : mesh.triangles[f]) normals[v] += cross;
  }
  for (Vec3& n : normals) {
    const double length = n.norm();
    if (length > 0) n /= length;
  }
  return normals;
}

namespace {

bool inside_triangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                     const Eigen::Vector2d& c) {
  return orient2d(a, b, p) >= 0 && orient2d(b, c, p) >= 0 && orient2d(c, a, p) >= 0;
}

}  // namespace

std::vector<Triangle> triangulate_polygon(const std::vector<Vec3>& positions,
                                          const std::vector<int>& polygon) {
  const size_t n = polygon.size();
  std::vector<Triangle> triangles;
  if (n < 3) return triangles;
  if (n == 3) return {{polygon[0], polygon[1], polygon[2]}};

  // Newell normal, then a 2D frame of the polygon's plane.
  Vec3 normal = Vec3::Zero();
  for (size_t i = 0; i < n; ++i) {
    const Vec3& p = positions[polygon[i]];
    const Vec3& q = positions[polygon[(i + 1) % n]];
    normal += Vec3((p.y() - q.y()) * (p.z() + q.z()), (p.z() - q.z()) * (p.x() + q.x()),
                   (p.x() - q.x()) * (p.y() + q.y()));
  }
  std::vector<Eigen::Vector2d> plane(n);
  if (normal.norm() > 0) {
    normal.normalize();
    const Vec3 u = normal.unitOrthogonal();
    const Vec3 w = normal.cross(u);
    for (size_t i = 0; i < n; ++i) {
      plane[i] = {positions[polygon[i]].dot(u), positions[polygon[i]].dot(w)};
    }
  }

  // Ear clipping: O(n²), polygons in mesh files are small.
  std::vector<int> ring(n);
  std::iota(ring.begin(), ring.end(), 0);
  while (ring.size() > 3 && normal.norm() > 0) {
    bool clipped = false;
    for (size_t i = 0; i < ring.size() && !clipped; ++i) {
      const int a = ring[(i + ring.size() - 1) % ring.size()];
      const int b = ring[i];
      const int c = ring[(i + 1) % ring.size()];
      if (orient2d(plane[a], plane[b], plane[c]) <= 0) continue;  // reflex or flat corner
      bool empty = true;
      for (int other : ring) {
        if (other == a || other == b || other == c) continue;
        if (inside_triangle(plane[other], plane[a], plane[b], plane[c])) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      triangles.push_back({polygon[a], polygon[b], polygon[c]});
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped) break;
  }
  // What remains (a triangle, or a degenerate/self-intersecting rest) is fanned from its first
  // corner.
  for (size_t i = 1; i + 1 < ring.size(); ++i) {
    triangles.push_back({polygon[ring[0]], polygon[ring[i]], polygon[ring[i + 1]]});
  }
  return triangles;
}

}  // namespace rangefill
