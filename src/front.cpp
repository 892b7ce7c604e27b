#include "rangefill/front.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <unordered_map>

#include "rangefill/errors.h"
#include "rangefill/geometry2d.h"

namespace rangefill {

namespace {

// The advancing front: a closed loop over fill vertices, oriented like the hole (the filled
// surface on the left of each edge), with the fill's positions and triangles.
class Front {
 public:
  Front(const Mesh& mesh, const MeshTopology& topology, const BoundaryLoop& hole,
        MlsSurface surface, const FrontOptions& options)
      : hole_(hole), surface_(std::move(surface)), options_(options) {
    const int n = static_cast<int>(hole.vertices.size());
    for (int k = 0; k < n; ++k) {
      positions_.push_back(mesh.positions[hole.vertices[k]]);
      normals_.push_back(surface_.reference_plane(positions_.back()).normal);
      next_.push_back((k + 1) % n);
      prev_.push_back((k + n - 1) % n);
      on_front_.push_back(1);
      edge_length_ += (mesh.positions[hole.vertices[(k + 1) % n]] - positions_.back()).norm() / n;
    }
    size_ = n;
    // Edges the fill must not create again: the mesh's between two boundary vertices.
    std::unordered_map<int, int> position_on_hole;
    for (int k = 0; k < n; ++k) position_on_hole.emplace(hole.vertices[k], k);
    for (int k = 0; k < n; ++k) {
      const int v = hole.vertices[k];
      for (int i = topology.faces_of_vertex_begin(v); i < topology.faces_of_vertex_end(v); ++i) {
        for (int w : mesh.triangles[topology.vertex_faces[i]]) {
          const auto other = position_on_hole.find(w);
          if (other != position_on_hole.end() && other->second != k) add_edge(k, other->second);
        }
      }
    }
    const double perimeter = edge_length_ * n;
    const double disk_area = perimeter * perimeter / (4 * M_PI);
    max_triangles_ =
        static_cast<size_t>(10 * disk_area / (0.43 * edge_length_ * edge_length_)) + 100;
  }

  Fill run() {
    double depth_scale = 1, phi = options_.phi;
    int stalls = 0, stagnant = 0;
    double shortest = front_length();
    while (size_ > 3) {
      const bool progress = make_convex(phi) | add_vertices(depth_scale) | make_convex(phi);
      // A front that does not get shorter extrudes the surface (round a thin tube's end, say)
      // instead of closing it; one that stalls cannot go on. Either is closed at once.
      const double length = front_length();
      stagnant = length < (1 - options_.min_shrinkage) * shortest ? 0 : stagnant + 1;
      shortest = std::min(shortest, length);
      if (stagnant >= options_.patience) break;
      if (progress) {
        stalls = 0;
        continue;
      }
      if (++stalls > options_.max_stalls) break;
      depth_scale *= options_.shrink;
      phi *= options_.shrink;
    }
    close_front();
    Fill fill;
    fill.boundary = hole_.vertices;
    fill.points.assign(positions_.begin() + hole_.vertices.size(), positions_.end());
    fill.triangles = std::move(triangles_);
    return fill;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw ProcessingError("hole " + std::to_string(hole_.id) + ": advancing front: " + why);
  }

  int first_on_front() const {
    for (int v = 0; v < static_cast<int>(on_front_.size()); ++v) {
      if (on_front_[v]) return v;
    }
    return -1;
  }

  // Angle of the hole at v, from v→prev to v→next counter-clockwise about v's normal, in [0, 2π).
  double hole_angle(int v) const {
    const Vec3 to_prev = positions_[prev_[v]] - positions_[v];
    const Vec3 to_next = positions_[next_[v]] - positions_[v];
    const double angle = std::atan2(normals_[v].dot(to_prev.cross(to_next)), to_prev.dot(to_next));
    return angle < 0 ? angle + 2 * M_PI : angle;
  }

  // Whether the triangle (a, b, c), counter-clockwise about the local MLS plane at its centroid,
  // is non-degenerate there, has no front edge crossing its sides (other than at shared corners)
  // and no other front vertex inside. `c` may be a point not on the front yet.
  bool clear_in_local_plane(int a, int b, const Vec3& c_position, int c) const {
    const Vec3 centroid = (positions_[a] + positions_[b] + c_position) / 3;
    const ReferencePlane plane = surface_.reference_plane(centroid, normals_[a] + normals_[b]);
    const Vec2 pa = plane.to_plane(positions_[a]), pb = plane.to_plane(positions_[b]),
               pc = plane.to_plane(c_position);
    if (!(orient2d(pa, pb, pc) > 0)) return false;
    const double radius =
        options_.search_radius * edge_length_ +
        std::max({(positions_[a] - centroid).norm(), (positions_[b] - centroid).norm(),
                  (c_position - centroid).norm()});
    for (int x = 0; x < static_cast<int>(on_front_.size()); ++x) {
      if (!on_front_[x]) continue;
      const int y = next_[x];
      if ((positions_[x] - centroid).norm() > radius &&
          (positions_[y] - centroid).norm() > radius) {
        continue;
      }
      // The other side of a thin part projects onto the same place but does not meet this one.
      if (normals_[x].dot(plane.normal) <= 0 && normals_[y].dot(plane.normal) <= 0) continue;
      const Vec2 px = plane.to_plane(positions_[x]), py = plane.to_plane(positions_[y]);
      const bool x_corner = x == a || x == b || x == c;
      const bool y_corner = y == a || y == b || y == c;
      if (!x_corner && orient2d(pa, pb, px) > 0 && orient2d(pb, pc, px) > 0 &&
          orient2d(pc, pa, px) > 0) {
        return false;  // a front vertex inside the triangle
      }
      const std::pair<const Vec2*, int> sides[3] = {{&pa, a}, {&pb, b}, {&pc, c}};
      for (int k = 0; k < 3; ++k) {
        const int s = sides[k].second, t = sides[(k + 1) % 3].second;
        if (x == s || x == t || y == s || y == t) continue;  // shares a corner with this side
        if (x_corner && y_corner) continue;
        if (segments_touch(*sides[k].first, *sides[(k + 1) % 3].first, px, py)) return false;
      }
    }
    return true;
  }

  // make-convex: clip the front vertex of smallest hole angle below φ whose ear is clear, again
  // and again.
  bool make_convex(double phi) {
    bool progress = false;
    std::vector<std::pair<double, int>> ears;
    while (size_ > 3) {
      ears.clear();
      for (int v = 0; v < static_cast<int>(on_front_.size()); ++v) {
        if (!on_front_[v]) continue;
        const double angle = hole_angle(v);
        if (angle < phi) ears.emplace_back(angle, v);
      }
      std::sort(ears.begin(), ears.end());
      int clipped = -1;
      for (const auto& [angle, v] : ears) {
        if (!has_edge(prev_[v], next_[v]) &&
            clear_in_local_plane(next_[v], v, positions_[prev_[v]], prev_[v])) {
          clipped = v;
          break;
        }
      }
      if (clipped < 0) break;
      const int u = prev_[clipped], w = next_[clipped];
      add_triangle({w, clipped, u});
      next_[u] = w;
      prev_[w] = u;
      on_front_[clipped] = 0;
      --size_;
      progress = true;
    }
    return progress;
  }

  // add-vertices: a new point on the perpendicular bisector of each front edge, towards the hole.
  bool add_vertices(double depth_scale) {
    std::vector<std::pair<int, int>> edges;
    for (int v = first_on_front(), k = 0; k < size_; v = next_[v], ++k)
      edges.emplace_back(v, next_[v]);
    bool progress = false;
    const size_t first_new = positions_.size();
    for (const auto& [a, b] : edges) {
      if (size_ <= 3) break;
      if (!on_front_[a] || next_[a] != b) continue;  // changed since the list was made
      const Vec3 midpoint = (positions_[a] + positions_[b]) / 2;
      const Vec3 facing = normals_[a] + normals_[b];
      const ReferencePlane plane = surface_.reference_plane(midpoint, facing);
      const Vec3 along = positions_[b] - positions_[a];
      const double e = along.norm();
      const Vec3 tangent = (along - plane.normal.dot(along) * plane.normal).normalized();
      const double square = std::max(4 * edge_length_ * edge_length_ - e * e, 0.25 * e * e);
      const double depth = std::sqrt(square) / 2 * depth_scale;  // d_e = √(4a² − e²)/2
      const auto projected =
          surface_.project(midpoint + depth * tangent.cross(plane.normal), facing);
      if (!projected || !projected->point.allFinite()) continue;
      if (too_close_to_front(projected->point, a, b, 0.4 * edge_length_ * depth_scale)) continue;
      if (!clear_in_local_plane(b, a, projected->point, -1)) continue;
      const int p = static_cast<int>(positions_.size());
      positions_.push_back(projected->point);
      normals_.push_back(projected->normal.dot(plane.normal) >= 0 ? projected->normal
                                                                  : -projected->normal);
      on_front_.push_back(1);
      next_.push_back(b);
      prev_.push_back(a);
      next_[a] = p;
      prev_[b] = p;
      ++size_;
      add_triangle({b, a, p});
      progress = true;
      if (triangles_.size() > max_triangles_) {
        fail("more than " + std::to_string(max_triangles_) +
             " triangles (the front does not close)");
      }
    }
    // The new points join the samples: the surface grows with the fill, curvature carries inwards.
    surface_.add_samples({positions_.begin() + first_new, positions_.end()},
                         {normals_.begin() + first_new, normals_.end()});
    return progress;
  }

  // The rest of the front in one go: the least-area triangulation avoiding the fill's edges.
  void close_front() {
    std::vector<int> ring;
    for (int v = first_on_front(), k = 0; k < size_; v = next_[v], ++k) ring.push_back(v);
    std::vector<Vec3> polygon;
    std::set<std::pair<int, int>> forbidden;
    for (int i = 0; i < size_; ++i) {
      polygon.push_back(positions_[ring[i]]);
      for (int j = i + 2; j < size_; ++j) {
        if (has_edge(ring[i], ring[j])) forbidden.emplace(i, j);
      }
    }
    const std::vector<Triangle> cap = triangulate_hole_polygon(polygon, forbidden);
    if (cap.empty())
      fail("the last " + std::to_string(size_) + " front vertices could not be closed");
    for (const Triangle& t : cap) triangles_.push_back({ring[t[0]], ring[t[1]], ring[t[2]]});
  }

  void add_edge(int a, int b) { edges_.emplace(std::min(a, b), std::max(a, b)); }
  bool has_edge(int a, int b) const { return edges_.count({std::min(a, b), std::max(a, b)}) > 0; }

  void add_triangle(const Triangle& t) {
    triangles_.push_back(t);
    for (int k = 0; k < 3; ++k) add_edge(t[k], t[(k + 1) % 3]);
  }

  double front_length() const {
    double length = 0;
    for (int v = first_on_front(), k = 0; k < size_; v = next_[v], ++k) {
      length += (positions_[next_[v]] - positions_[v]).norm();
    }
    return length;
  }

  bool too_close_to_front(const Vec3& p, int a, int b, double distance) const {
    for (int x = 0; x < static_cast<int>(on_front_.size()); ++x) {
      if (on_front_[x] && x != a && x != b && (positions_[x] - p).norm() < distance) return true;
    }
    return false;
  }

  const BoundaryLoop& hole_;
  MlsSurface surface_;
  const FrontOptions& options_;
  std::vector<Vec3> positions_, normals_;  // fill vertices: the hole's, then new points
  std::vector<int> next_, prev_;
  std::vector<char> on_front_;
  std::vector<Triangle> triangles_;
  std::set<std::pair<int, int>> edges_;  // undirected, fill-vertex ids: the fill's and the mesh's
  int size_ = 0;
  double edge_length_ = 0;    // a: the mean boundary edge length
  size_t max_triangles_ = 0;  // ten times what a flat disk of the same perimeter would take
};

}  // namespace

Fill fill_by_front(const Mesh& mesh, const MeshTopology& topology, const BoundaryLoop& hole,
                   MlsSurface surface, const FrontOptions& options) {
  if (hole.vertices.size() < 3) {
    throw ProcessingError("hole " + std::to_string(hole.id) + ": fewer than 3 boundary vertices");
  }
  return Front(mesh, topology, hole, std::move(surface), options).run();
}

}  // namespace rangefill
