#include "rangefill/holes.h"

#include <algorithm>

namespace rangefill {

namespace {

// The boundary half-edge that follows boundary half-edge `h` (which ends at vertex b) on its loop:
// rotate around b through the faces of h's fan until a boundary half-edge leaves b. Returns -1 when
// the fan is cut by a non-manifold or misoriented edge.
int next_in_fan(const MeshTopology& topology, int h) {
  int out = next_halfedge(h);  // leaves b inside the face of h
  while (topology.opposite[out] >= 0) {
    out = next_halfedge(topology.opposite[out]);
    if (out == next_halfedge(h)) return -1;  // went all the way round: cannot happen on a boundary
  }
  return topology.opposite[out] == kBoundary ? out : -1;
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

  for (int start = 0; start < halfedge_count; ++start) {
    if (topology.opposite[start] != kBoundary || visited[start]) continue;
    std::vector<int> loop_halfedges;
    int h = start;
    bool closed = false;
    while (h >= 0 && !visited[h]) {
      visited[h] = 1;
      loop_halfedges.push_back(h);
      h = next_in_fan(topology, h);
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

  // Mark the longest loop of each component (ties: the lower id); on an open scan it is the outer
  // border.
  std::vector<int> longest(topology.component_count, -1);
  for (const BoundaryLoop& loop : holes.loops) {
    int& best = longest[loop.component];
    if (best < 0 || loop.perimeter > holes.loops[best].perimeter) best = loop.id;
  }
  for (int id : longest) {
    if (id >= 0) holes.loops[id].longest_in_component = true;
  }
  return holes;
}

}  // namespace rangefill
