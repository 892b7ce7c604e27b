#include "rangefill/hole/holes.h"

#include <algorithm>
#include <cmath>

namespace rangefill {

namespace {

// Angle of `direction` from `reference`, counter-clockwise about `normal`, in [0, 2π).
double ccw_angle(const Vec3& reference, const Vec3& direction, const Vec3& normal) {
  const double angle = std::atan2(normal.dot(reference.cross(direction)), reference.dot(direction));
  return angle < 0 ? angle + 2 * M_PI : angle;
}

// The boundary half-edges of a mesh, followed from one to the next round each loop.
class BoundaryWalk {
 public:
  BoundaryWalk(const Mesh& mesh, const MeshTopology& topology, const FaceComponents& components)
      : mesh_(mesh),
        topology_(topology),
        components_(components),
        visited_(topology.opposite.size(), false) {
    for (int h = 0; h < static_cast<int>(topology.opposite.size()); ++h) {
      if (topology.opposite[h] == kBoundary)
        leaving_.emplace_back(topology.halfedge_source(mesh, h), h);
    }
    std::sort(leaving_.begin(), leaving_.end());
  }

  // Vertices on more than two boundary edges, ascending.
  std::vector<int> pinched_vertices() const {
    std::vector<int> pinched;
    for (size_t i = 1; i < leaving_.size(); ++i) {
      const int v = leaving_[i].first;
      if (leaving_[i - 1].first == v && (pinched.empty() || pinched.back() != v))
        pinched.push_back(v);
    }
    return pinched;
  }

  // The half-edges walked from boundary half-edge `start` (not yet walked) until the walk comes
  // back to it or cannot go on; `closed` tells which.
  std::vector<int> walk(int start, bool& closed) {
    std::vector<int> halfedges;
    int h = start;
    closed = false;
    while (h >= 0 && !visited_[h]) {
      visited_[h] = 1;
      halfedges.push_back(h);
      h = next_on_loop(h, start);
      if (h == start) closed = true;
    }
    return halfedges;
  }

  bool walked(int h) const { return visited_[h]; }

 private:
  // The boundary half-edge that continues the loop after h = a→b. Where several leave b (loops
  // touch at b), the hole on the right of h is the angular gap from b→a counter-clockwise (about
  // the vertex normal) up to the next fan of faces of the same component, whose first edge is the
  // one to take.
  int next_on_loop(int h, int start) const {
    const int a = topology_.halfedge_source(mesh_, h), b = topology_.halfedge_target(mesh_, h);
    // A loop stays within the component of its faces.
    const int component = components_.of_face[halfedge_face(h)];
    auto available = [&](int candidate) {
      return (!visited_[candidate] || candidate == start) &&
             components_.of_face[halfedge_face(candidate)] == component;
    };
    const auto first = std::lower_bound(leaving_.begin(), leaving_.end(), std::pair(b, 0));
    const auto last = std::lower_bound(first, leaving_.end(), std::pair(b + 1, 0));
    if (last - first == 1) return available(first->second) ? first->second : -1;
    const Vec3 reference = mesh_.positions[a] - mesh_.positions[b];
    const Vec3 normal = vertex_normal(mesh_, topology_, b);
    int best = -1;
    double best_angle = 0;
    for (auto it = first; it != last; ++it) {
      const int candidate = it->second;
      if (!available(candidate)) continue;
      const Vec3 direction =
          mesh_.positions[topology_.halfedge_target(mesh_, candidate)] - mesh_.positions[b];
      const double angle = ccw_angle(reference, direction, normal);
      if (best < 0 || angle < best_angle) {
        best = candidate;
        best_angle = angle;
      }
    }
    return best;
  }

  const Mesh& mesh_;
  const MeshTopology& topology_;
  const FaceComponents& components_;
  std::vector<bool> visited_;                 // per half-edge
  std::vector<std::pair<int, int>> leaving_;  // (source, half-edge) of the boundary's, ascending
};

// The loop of a closed walk: its vertices, perimeter and vector area (eq. 1).
BoundaryLoop loop_of(const Mesh& mesh, const MeshTopology& topology,
                     const FaceComponents& components, const std::vector<int>& halfedges, int id) {
  BoundaryLoop loop;
  loop.id = id;
  loop.component = components.of_face[halfedge_face(halfedges.front())];
  Vec3 vector_area = Vec3::Zero();
  for (int e : halfedges) {
    const Vec3& p = mesh.positions[topology.halfedge_source(mesh, e)];
    const Vec3& q = mesh.positions[topology.halfedge_target(mesh, e)];
    loop.vertices.push_back(topology.halfedge_source(mesh, e));
    loop.perimeter += (q - p).norm();
    vector_area += p.cross(q);
  }
  loop.area = 0.5 * vector_area.norm();
  return loop;
}

}  // namespace

HoleSet find_holes(const Mesh& mesh, const MeshTopology& topology) {
  HoleSet holes;
  const FaceComponents components = face_components(mesh, topology);
  BoundaryWalk walk(mesh, topology, components);
  holes.pinched_vertices = walk.pinched_vertices();
  for (int start = 0; start < static_cast<int>(topology.opposite.size()); ++start) {
    if (topology.opposite[start] != kBoundary || walk.walked(start)) continue;
    bool closed = false;
    const std::vector<int> halfedges = walk.walk(start, closed);
    if (closed) {
      holes.loops.push_back(
          loop_of(mesh, topology, components, halfedges, static_cast<int>(holes.loops.size())));
    } else {
      holes.open_boundary_edges += static_cast<int>(halfedges.size());
    }
  }
  holes.component_areas.assign(components.count, 0.0);
  for (int f = 0; f < mesh.face_count(); ++f) {
    holes.component_areas[components.of_face[f]] += 0.5 * triangle_cross(mesh, f).norm();
  }
  for (BoundaryLoop& loop : holes.loops) {
    const double total = holes.component_areas[loop.component];
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
