#include "rangefill/fillers/front.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>
#include <unordered_map>

#include "rangefill/core/errors.h"
#include "rangefill/core/geometry2d.h"
#include "rangefill/core/intersection.h"
#include "rangefill/fillers/loop_patch.h"

namespace rangefill {

namespace {

// The advancing front: a closed loop over fill vertices, oriented like the hole (the filled
// surface on the left of each edge), with the fill's positions and triangles.
class Front {
 public:
  Front(const Mesh& mesh, const MeshTopology& topology, const IntersectionIndex& faces,
        const BoundaryLoop& hole, MlsSurface surface, const FrontOptions& options)
      : faces_(faces), hole_(hole), surface_(std::move(surface)), options_(options) {
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
      for_each_face_of_vertex(topology, v, [&](int face) {
        for (int w : mesh.triangles[face]) {
          const auto other = position_on_hole.find(w);
          if (other != position_on_hole.end() && other->second != k) add_edge(k, other->second);
        }
      });
    }
    const double perimeter = edge_length_ * n;
    const double disk_area = perimeter * perimeter / (4 * M_PI);
    max_triangles_ =
        static_cast<size_t>(10 * disk_area / (0.43 * edge_length_ * edge_length_)) + 100;
  }

  FillOutcome run() {
    double depth_scale = 1, phi = options_.phi;
    int stalls = 0, stagnant = 0;
    double shortest = front_length();
    while (size_ > 3) {
      // All three steps run, in this order (the operands of a | b | c are not sequenced).
      bool progress = make_convex(phi);
      progress |= add_vertices(depth_scale);
      if (!failure_.empty()) return Refused{Refusal::front_stuck, failure_};
      progress |= make_convex(phi);
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
    if (!close_front()) {
      return Refused{Refusal::front_stuck,
                     "the last " + std::to_string(size_) + " front vertices could not be closed"};
    }
    Fill fill;
    fill.boundary = hole_.vertices;
    fill.points.assign(positions_.begin() + hole_.vertices.size(), positions_.end());
    fill.triangles = std::move(triangles_);
    return fill;
  }

 private:
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

  // Whether the triangle over fill vertices (a, b, c) (c may be -1 with position `c_position`)
  // meets neither the mesh nor an earlier fill triangle beyond the vertices they share.
  bool free_in_space(int a, int b, const Vec3& c_position, int c) const {
    const std::array<Vec3, 3> candidate = {positions_[a], positions_[b], c_position};
    const int boundary_size = static_cast<int>(hole_.vertices.size());
    auto mesh_id = [&](int v) { return v >= 0 && v < boundary_size ? hole_.vertices[v] : -1; };
    if (!faces_
             .intersecting_faces(candidate[0], candidate[1], candidate[2],
                                 {mesh_id(a), mesh_id(b), mesh_id(c)})
             .empty()) {
      return false;
    }
    const Vec3 centre = (candidate[0] + candidate[1] + candidate[2]) / 3;
    const double reach = std::max({(candidate[0] - centre).norm(), (candidate[1] - centre).norm(),
                                   (candidate[2] - centre).norm()});
    for (const Triangle& t : triangles_) {
      const std::array<Vec3, 3> other = {positions_[t[0]], positions_[t[1]], positions_[t[2]]};
      const Vec3 other_centre = (other[0] + other[1] + other[2]) / 3;
      const double other_reach =
          std::max({(other[0] - other_centre).norm(), (other[1] - other_centre).norm(),
                    (other[2] - other_centre).norm()});
      if ((centre - other_centre).norm() > reach + other_reach) continue;
      if (triangles_intersect(candidate, other, {a, b, c}, t)) return false;
    }
    return true;
  }

  // Cuts the ear at front vertex v: the triangle (next, v, prev) joins the fill, v leaves the
  // front.
  void clip(int v) {
    const int u = prev_[v], w = next_[v];
    add_triangle({w, v, u});
    next_[u] = w;
    prev_[w] = u;
    on_front_[v] = 0;
    --size_;
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
            clear_in_local_plane(next_[v], v, positions_[prev_[v]], prev_[v]) &&
            free_in_space(next_[v], v, positions_[prev_[v]], prev_[v])) {
          clipped = v;
          break;
        }
      }
      if (clipped < 0) break;
      clip(clipped);
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
      if (!free_in_space(b, a, projected->point, -1)) continue;
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
        failure_ =
            "more than " + std::to_string(max_triangles_) + " triangles (the front does not close)";
        return false;
      }
    }
    // The new points join the samples: the surface grows with the fill, curvature carries inwards.
    surface_.add_samples({positions_.begin() + first_new, positions_.end()},
                         {normals_.begin() + first_new, normals_.end()});
    return progress;
  }

  // The rest of the front in one go: ear clipping in the plane of its Newell normal, or else the
  // least-area triangulation; the first whose triangles are new edges and free in space. False
  // when neither closes it.
  bool close_front() {
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
    std::vector<int> order(size_);
    std::iota(order.begin(), order.end(), 0);
    std::vector<Triangle> ears = triangulate_polygon(polygon, order);
    for (Triangle& t : ears) std::swap(t[1], t[2]);  // the front's edges reversed
    for (const std::vector<Triangle>& cap :
         {ears, triangulate_loop_least_area(polygon, forbidden)}) {
      const size_t kept = triangles_.size();
      const std::set<std::pair<int, int>> edges = edges_;
      bool valid = !cap.empty();
      for (const Triangle& t : cap) {
        const Triangle triangle = {ring[t[0]], ring[t[1]], ring[t[2]]};
        for (int k = 0; k < 3 && valid; ++k) {
          const int a = triangle[k], b = triangle[(k + 1) % 3];
          valid = next_[a] == b || next_[b] == a || !edges.count({std::min(a, b), std::max(a, b)});
        }
        valid =
            valid && free_in_space(triangle[0], triangle[1], positions_[triangle[2]], triangle[2]);
        if (!valid) break;
        add_triangle(triangle);
      }
      if (valid) return true;
      triangles_.resize(kept);
      edges_ = edges;
    }
    return clip_ears_in_space();
  }

  // Greedy ear clipping by the smallest angle in space, each ear a new edge and free in space:
  // for a small front twisted too much for a plane. False if it gets stuck.
  bool clip_ears_in_space() {
    while (size_ > 3) {
      int best = -1;
      double best_angle = M_PI;
      for (int v = 0; v < static_cast<int>(on_front_.size()); ++v) {
        if (!on_front_[v]) continue;
        const Vec3 to_prev = positions_[prev_[v]] - positions_[v];
        const Vec3 to_next = positions_[next_[v]] - positions_[v];
        const double angle = std::atan2(to_prev.cross(to_next).norm(), to_prev.dot(to_next));
        if (angle < best_angle && !has_edge(prev_[v], next_[v]) &&
            free_in_space(next_[v], v, positions_[prev_[v]], prev_[v])) {
          best = v;
          best_angle = angle;
        }
      }
      if (best < 0) return false;
      clip(best);
    }
    return close_triangle();
  }

  // The last three front vertices a→b→c as the triangle (c, b, a), if it is free in space.
  bool close_triangle() {
    const int a = first_on_front(), b = next_[a], c = next_[b];
    if (has_edge(a, c) && next_[c] != a) return false;
    if (!free_in_space(c, b, positions_[a], a)) return false;
    add_triangle({c, b, a});
    return true;
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

  const IntersectionIndex& faces_;
  const BoundaryLoop& hole_;
  MlsSurface surface_;
  const FrontOptions& options_;
  std::vector<Vec3> positions_, normals_;  // fill vertices: the hole's, then new points
  std::vector<int> next_, prev_;
  std::vector<char> on_front_;
  std::vector<Triangle> triangles_;
  std::set<std::pair<int, int>> edges_;  // undirected, fill-vertex ids: the fill's and the mesh's
  int size_ = 0;
  std::string failure_;       // why the front stopped without closing
  double edge_length_ = 0;    // a: the mean boundary edge length
  size_t max_triangles_ = 0;  // ten times what a flat disk of the same perimeter would take
};

}  // namespace

FillOutcome fill_by_front(const Mesh& mesh, const MeshTopology& topology,
                          const IntersectionIndex& faces, const BoundaryLoop& hole,
                          MlsSurface surface, const FrontOptions& options) {
  if (hole.vertices.size() < 3) {
    throw InvalidInput("hole " + std::to_string(hole.id) + ": fewer than 3 boundary vertices");
  }
  return Front(mesh, topology, faces, hole, std::move(surface), options).run();
}

}  // namespace rangefill
