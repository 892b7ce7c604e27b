#include "rangefill/repair/holes.h"

#include <algorithm>
#include <cmath>

namespace rangefill {

namespace {

// Angle of `direction` from `reference`, counter-clockwise about `normal`, in [0, 2π).
double ccw_angle(const Vec3& reference, const Vec3& direction, const Vec3& normal) {
  const double angle = std::atan2(normal.dot(reference.cross(direction)), reference.dot(direction));
  return angle < 0 ? angle + 2 * M_PI : angle;
}

// Area-weighted normal of the faces around vertex v.
Vec3 vertex_normal(const Mesh& mesh, const MeshTopology& topology, int v) {
  Vec3 normal = Vec3::Zero();
  for (int i = topology.faces_of_vertex_begin(v); i < topology.faces_of_vertex_end(v); ++i) {
    normal += triangle_cross(mesh, topology.vertex_faces[i]);
  }
  return normal;
}

}  // namespace

HoleSet find_holes(const Mesh& mesh, const MeshTopology& topology) {
  HoleSet holes;
  const int halfedge_count = static_cast<int>(topology.opposite.size());
  std::vector<char> visited(halfedge_count, 0);
  std::vector<int> boundary_degree(mesh.vertex_count(), 0);
  for (int h = 0; h < halfedge_count; ++h) {
    if (topology.opposite[h] == kBoundary) ++boundary_degree[topology.halfedge_source(mesh, h)];
  }
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (boundary_degree[v] > 1) holes.pinched_vertices.push_back(v);
  }

  // Boundary half-edges leaving each vertex (CSR).
  std::vector<int> out_offsets(mesh.vertex_count() + 1, 0);
  for (int v = 0; v < mesh.vertex_count(); ++v)
    out_offsets[v + 1] = out_offsets[v] + boundary_degree[v];
  std::vector<int> out_halfedges(out_offsets.back());
  {
    std::vector<int> cursor(out_offsets.begin(), out_offsets.end() - 1);
    for (int h = 0; h < halfedge_count; ++h) {
      if (topology.opposite[h] == kBoundary)
        out_halfedges[cursor[topology.halfedge_source(mesh, h)]++] = h;
    }
  }

  // The boundary half-edge that continues the loop after h = a→b. Where several leave b (loops
  // touch at b), the hole on the right of h is the angular gap from b→a counter-clockwise (about
  // the vertex normal) up to the next fan of faces of the same component, whose first edge is the
  // one to take.
  auto next_on_loop = [&](int h, int start) {
    const int a = topology.halfedge_source(mesh, h), b = topology.halfedge_target(mesh, h);
    // A loop stays within the component of its faces.
    const int component = topology.face_component[halfedge_face(h)];
    auto available = [&](int candidate) {
      return (!visited[candidate] || candidate == start) &&
             topology.face_component[halfedge_face(candidate)] == component;
    };
    if (boundary_degree[b] == 1) {
      const int only = out_halfedges[out_offsets[b]];
      return available(only) ? only : -1;
    }
    const Vec3 reference = mesh.positions[a] - mesh.positions[b];
    const Vec3 normal = vertex_normal(mesh, topology, b);
    int best = -1;
    double best_angle = 0;
    for (int i = out_offsets[b]; i < out_offsets[b + 1]; ++i) {
      const int candidate = out_halfedges[i];
      if (!available(candidate)) continue;
      const Vec3 direction =
          mesh.positions[topology.halfedge_target(mesh, candidate)] - mesh.positions[b];
      const double angle = ccw_angle(reference, direction, normal);
      if (best < 0 || angle < best_angle) {
        best = candidate;
        best_angle = angle;
      }
    }
    return best;
  };

  for (int start = 0; start < halfedge_count; ++start) {
    if (topology.opposite[start] != kBoundary || visited[start]) continue;
    std::vector<int> loop_halfedges;
    int h = start;
    bool closed = false;
    while (h >= 0 && !visited[h]) {
      visited[h] = 1;
      loop_halfedges.push_back(h);
      h = next_on_loop(h, start);
      if (h == start) closed = true;
    }
    if (!closed) {
      holes.open_boundary_edges += static_cast<int>(loop_halfedges.size());
      continue;
    }
    BoundaryLoop loop;
    loop.id = static_cast<int>(holes.loops.size());
    loop.component = topology.face_component[halfedge_face(start)];
    Vec3 vector_area = Vec3::Zero();
    for (int e : loop_halfedges) {
      const Vec3& p = mesh.positions[topology.halfedge_source(mesh, e)];
      const Vec3& q = mesh.positions[topology.halfedge_target(mesh, e)];
      loop.vertices.push_back(topology.halfedge_source(mesh, e));
      loop.perimeter += (q - p).norm();
      vector_area += p.cross(q);
    }
    loop.area = 0.5 * vector_area.norm();
    holes.loops.push_back(std::move(loop));
  }

  std::vector<double> component_area(topology.component_count, 0.0);
  for (int f = 0; f < mesh.face_count(); ++f) {
    component_area[topology.face_component[f]] += 0.5 * triangle_cross(mesh, f).norm();
  }
  for (BoundaryLoop& loop : holes.loops) {
    const double total = component_area[loop.component];
    loop.area_share = total > 0 ? loop.area / total : 0;
  }
  return holes;
}

std::vector<int> sorted_vertices(const BoundaryLoop& loop) {
  std::vector<int> vertices = loop.vertices;
  std::sort(vertices.begin(), vertices.end());
  return vertices;
}

bool is_border(const BoundaryLoop& loop, double border_share) {
  return border_share > 0 && loop.area_share >= border_share;
}

}  // namespace rangefill
