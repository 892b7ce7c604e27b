// CGAL's angle smoothing and Euler operations (heavy headers) on a fill and the ring of faces
// around its loop.
#include "rangefill/hole/patch_angles.h"

#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include <CGAL/Polygon_mesh_processing/angle_and_area_smoothing.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include "core/cgal_surface_mesh.h"
#include "core/cgal_triangles.h"
#include "rangefill/core/intersection.h"

namespace rangefill {

namespace {

using namespace cgal_surface_mesh;
namespace pmp = CGAL::Polygon_mesh_processing;

// Faces under this smallest angle after the smoothing get a vertex nearer their short edge (12°:
// a margin over the 10° that meshing tools take for a sliver), in up to this many rounds.
const double kSliverAngle = 12 * M_PI / 180;
constexpr int kSplitRounds = 3;

// The angle at corner p of the triangle (p, q, r), in radians.
double corner_angle(const Kernel::Point_3& p, const Kernel::Point_3& q, const Kernel::Point_3& r) {
  const Kernel::Vector_3 u = q - p, v = r - p;
  return std::atan2(std::sqrt(CGAL::cross_product(u, v).squared_length()), u * v);
}

// The smallest angle of the triangle (p, q, r).
double smallest_angle(const Kernel::Point_3& p, const Kernel::Point_3& q,
                      const Kernel::Point_3& r) {
  return std::min({corner_angle(p, q, r), corner_angle(q, r, p), corner_angle(r, p, q)});
}

// The normal of the triangle (p, q, r), its length twice the area; null for a degenerate one
// (CGAL::normal asserts on those in builds without NDEBUG, and a fill may hold one: the caller's
// check refuses it after this pass).
Kernel::Vector_3 normal(const Kernel::Point_3& p, const Kernel::Point_3& q,
                        const Kernel::Point_3& r) {
  return CGAL::cross_product(q - p, r - p);
}

bool in_fill(FaceIndex f, size_t fill_faces) {
  return f != SurfaceMesh::null_face() && static_cast<size_t>(f) >= fill_faces;
}

// The smallest angle of face f.
double smallest_angle(const SurfaceMesh& surface, FaceIndex f) {
  const auto h = surface.halfedge(f);
  return smallest_angle(surface.point(surface.source(h)), surface.point(surface.target(h)),
                        surface.point(surface.target(surface.next(h))));
}

Vec3 to_vec(const Kernel::Point_3& p) {
  return Vec3(p.x(), p.y(), p.z());
}

// The faces of the part outside the fill (its first `fill_faces`), for crossing tests.
class Surroundings {
 public:
  Surroundings(const SurfaceMesh& surface, size_t fill_faces) : surface_(surface) {
    for (FaceIndex f : surface.faces()) {
      if (static_cast<size_t>(f) >= fill_faces) continue;
      std::array<VertexIndex, 3> corners;
      int k = 0;
      for (VertexIndex v : surface.vertices_around_face(surface.halfedge(f))) corners[k++] = v;
      faces_.push_back(corners);
      boxes_.push_back(box(corners[0], corners[1], corners[2]));
    }
  }

  // Whether the triangle (a, b, c) of the part's vertices crosses one of the faces beyond the
  // vertices they share (core/intersection.h's rules).
  bool crossed_by(VertexIndex a, VertexIndex b, VertexIndex c) const {
    const CGAL::Bbox_3 bounds = box(a, b, c);
    const std::array<Vec3, 3> triangle = {position(a), position(b), position(c)};
    const Triangle ids = {static_cast<int>(a), static_cast<int>(b), static_cast<int>(c)};
    for (size_t i = 0; i < faces_.size(); ++i) {
      if (!CGAL::do_overlap(bounds, boxes_[i])) continue;
      const auto& [p, q, r] = faces_[i];
      if (triangles_intersect(triangle, {position(p), position(q), position(r)}, ids,
                              {static_cast<int>(p), static_cast<int>(q), static_cast<int>(r)})) {
        return true;
      }
    }
    return false;
  }

 private:
  Vec3 position(VertexIndex v) const { return to_vec(surface_.point(v)); }
  CGAL::Bbox_3 box(VertexIndex a, VertexIndex b, VertexIndex c) const {
    return surface_.point(a).bbox() + surface_.point(b).bbox() + surface_.point(c).bbox();
  }

  const SurfaceMesh& surface_;
  std::vector<std::array<VertexIndex, 3>> faces_;
  std::vector<CGAL::Bbox_3> boxes_;
};

// Lawson's flips inside the fill (faces from `fill_faces` on). An inner edge is flipped when its
// new triangles cross no face around the fill and either its triangles cross one (the fill
// folds over a tooth of the loop; the flip untangles it) or the flip raises the smaller of the two
// triangles' smallest angles, the two faces bend by less than 60° (the surface keeps its shape)
// and the new triangles face as the old ones. The new edge must not exist yet. Slivers over two
// nearly collinear loop edges go this way.
void flip_to_max_min_angle(SurfaceMesh& surface, size_t fill_faces) {
  const Surroundings surroundings(surface, fill_faces);
  constexpr double kMinBendCosine = 0.5;
  for (int sweep = 0; sweep < 10; ++sweep) {
    bool flipped = false;
    for (auto edge : surface.edges()) {
      const auto h = surface.halfedge(edge), o = surface.opposite(h);
      if (!in_fill(surface.face(h), fill_faces) || !in_fill(surface.face(o), fill_faces)) continue;
      const VertexIndex a = surface.source(h), b = surface.target(h);
      const VertexIndex c = surface.target(surface.next(h)), d = surface.target(surface.next(o));
      if (surface.halfedge(c, d) != SurfaceMesh::null_halfedge()) continue;
      const auto &pa = surface.point(a), &pb = surface.point(b);
      const auto &pc = surface.point(c), &pd = surface.point(d);
      // Faces (a, b, c) and (b, a, d) become (a, d, c) and (d, b, c).
      const auto m1 = normal(pa, pd, pc), m2 = normal(pd, pb, pc);
      if (m1 == CGAL::NULL_VECTOR || m2 == CGAL::NULL_VECTOR) continue;
      const bool tangled = surroundings.crossed_by(a, b, c) || surroundings.crossed_by(b, a, d);
      if (!tangled) {
        const double before = std::min(smallest_angle(pa, pb, pc), smallest_angle(pb, pa, pd));
        const double after = std::min(smallest_angle(pa, pd, pc), smallest_angle(pd, pb, pc));
        if (after <= before + 1e-9) continue;
        const auto n1 = normal(pa, pb, pc), n2 = normal(pb, pa, pd);
        if (!(n1 * n2 >= kMinBendCosine * std::sqrt(n1.squared_length() * n2.squared_length()))) {
          continue;  // bent by 60° or more, or a triangle without area
        }
        if (m1 * n1 <= 0 || m1 * n2 <= 0 || m2 * n1 <= 0 || m2 * n2 <= 0) continue;
      }
      if (surroundings.crossed_by(a, d, c) || surroundings.crossed_by(d, b, c)) continue;
      CGAL::Euler::flip_edge(h, surface);
      flipped = true;
    }
    if (!flipped) break;
  }
}

// Moves the fill's new vertices (from `new_vertices` on) over the fill's faces (from `fill_faces`
// on) towards larger angles, unless a face of the part is degenerate; CGAL makes no move that
// shrinks an angle or lets the surface self-intersect, and projects each back onto the fill as it
// was.
void smooth_angles(SurfaceMesh& surface, size_t fill_faces, size_t new_vertices) {
  // CGAL's precondition: no degenerate face (the input's or the fill's; the caller's check
  // refuses a degenerate fill).
  for (FaceIndex f : surface.faces()) {
    if (pmp::is_degenerate_triangle_face(f, surface)) return;
  }
  std::vector<FaceIndex> faces;
  for (FaceIndex f : surface.faces()) {
    if (static_cast<size_t>(f) >= fill_faces) faces.push_back(f);
  }
  auto fixed = surface.add_property_map<VertexIndex, bool>("v:fixed", false).first;
  for (VertexIndex v : surface.vertices()) fixed[v] = static_cast<size_t>(v) < new_vertices;
  // Five sweeps: beyond them the smallest angles hardly rise, and each sweep checks the part for
  // self-intersections.
  pmp::angle_and_area_smoothing(
      faces, surface,
      CGAL::parameters::number_of_iterations(5).use_area_smoothing(false).vertex_is_constrained_map(
          fixed));
  surface.remove_property_map(fixed);
}

// Splits at its midpoint the longest edge inside the fill of each fill face whose smallest angle
// is under `threshold`, and joins the new vertex to the two opposite corners. A short loop edge met
// at long range gets a vertex nearer to it, for the smoothing to place. Returns whether an edge was
// split.
bool split_at_slivers(SurfaceMesh& surface, size_t fill_faces, double threshold) {
  std::vector<FaceIndex> slivers;
  for (FaceIndex f : surface.faces()) {
    if (in_fill(f, fill_faces) && smallest_angle(surface, f) < threshold) slivers.push_back(f);
  }
  bool split = false;
  for (FaceIndex f : slivers) {
    if (smallest_angle(surface, f) >= threshold) continue;  // a neighbour's split mended it
    // The longest of its edges inside the fill (a loop edge stays whole).
    auto longest = SurfaceMesh::null_halfedge();
    double longest_length = 0;
    for (auto h : surface.halfedges_around_face(surface.halfedge(f))) {
      const double length = CGAL::squared_distance(surface.point(surface.source(h)),
                                                   surface.point(surface.target(h)));
      if (in_fill(surface.face(surface.opposite(h)), fill_faces) && length > longest_length) {
        longest = h;
        longest_length = length;
      }
    }
    if (longest == SurfaceMesh::null_halfedge()) continue;
    const auto midpoint = CGAL::midpoint(surface.point(surface.source(longest)),
                                         surface.point(surface.target(longest)));
    // split_edge: `added` runs to the new vertex, then `longest` from it (both faces are quads).
    const auto added = CGAL::Euler::split_edge(longest, surface);
    surface.point(surface.target(added)) = midpoint;
    CGAL::Euler::split_face(added, surface.next(longest), surface);
    const auto back = surface.opposite(longest);  // into the new vertex on the other face
    CGAL::Euler::split_face(back, surface.next(surface.opposite(added)), surface);
    split = true;
  }
  return split;
}

// The fill's vertex positions: its loop's, then its points.
std::vector<Vec3> fill_positions(const Mesh& mesh, const Fill& fill) {
  std::vector<Vec3> positions;
  for (int v : fill.boundary) positions.push_back(mesh.positions[v]);
  positions.insert(positions.end(), fill.points.begin(), fill.points.end());
  return positions;
}

// The colours of `moved`'s points: those of `original` (the same fill before its points moved
// over it) where each now lies, interpolated across the original triangle nearest to it.
std::vector<Rgb> colours_where_moved(const Mesh& mesh, const Fill& original, const Fill& moved) {
  std::vector<Rgb> colours;
  for (int v : original.boundary) colours.push_back(mesh.colors[v]);
  colours.insert(colours.end(), original.colors.begin(), original.colors.end());
  Mesh own;
  own.positions = fill_positions(mesh, original);
  own.triangles = original.triangles;
  std::vector<int> all(own.triangles.size());
  std::iota(all.begin(), all.end(), 0);
  const std::vector<cgal_triangles::CgalTriangle> triangles =
      cgal_triangles::to_triangles(own, all);
  const cgal_triangles::AabbTree tree(triangles.begin(), triangles.end());
  std::vector<Rgb> result = original.colors;
  result.resize(moved.points.size());
  for (size_t i = 0; i < moved.points.size(); ++i) {
    if (i < original.points.size() && moved.points[i] == original.points[i]) continue;
    const auto [closest, primitive] =
        tree.closest_point_and_primitive(cgal_triangles::to_point(moved.points[i]));
    const Triangle& t = own.triangles[primitive - triangles.begin()];
    const Vec3 &a = own.positions[t[0]], &b = own.positions[t[1]], &c = own.positions[t[2]];
    const Vec3 p(closest.x(), closest.y(), closest.z());
    const Vec3 normal = (b - a).cross(c - a);
    const double area = normal.squaredNorm();
    if (!(area > 0)) {
      result[i] = colours[t[0]];
      continue;
    }
    const float weight_a = static_cast<float>((c - b).cross(p - b).dot(normal) / area);
    const float weight_b = static_cast<float>((a - c).cross(p - c).dot(normal) / area);
    result[i] = weight_a * colours[t[0]] + weight_b * colours[t[1]] +
                (1 - weight_a - weight_b) * colours[t[2]];
  }
  return result;
}

}  // namespace

Fill with_larger_angles(const Mesh& mesh, const MeshTopology& topology, Fill fill) {
  if (std::set<int>(fill.boundary.begin(), fill.boundary.end()).size() < fill.boundary.size()) {
    return fill;  // a loop through one vertex twice: no manifold part to flip and smooth on
  }
  MeshPart part;
  for (int face : faces_within_rings(mesh, topology, fill.boundary, 1)) {
    if (!part.add_face(mesh, face)) return fill;
  }
  const size_t fill_faces = part.surface.number_of_faces();
  const size_t new_vertices = part.surface.number_of_vertices();
  // The fill's vertex ids: the loop's vertices in the part, then the new points.
  std::vector<VertexIndex> vertex;
  for (int v : fill.boundary) vertex.push_back(part.local.at(v));
  for (const Vec3& p : fill.points)
    vertex.push_back(part.surface.add_vertex({p.x(), p.y(), p.z()}));
  for (const Triangle& t : fill.triangles) {
    if (part.surface.add_face(vertex[t[0]], vertex[t[1]], vertex[t[2]]) ==
        SurfaceMesh::null_face()) {
      return fill;
    }
  }
  std::optional<Fill> original;  // to colour the moved points (colours come with the mesh's)
  if (!fill.colors.empty() && !mesh.colors.empty()) original = fill;
  flip_to_max_min_angle(part.surface, fill_faces);
  smooth_angles(part.surface, fill_faces, new_vertices);
  flip_to_max_min_angle(part.surface, fill_faces);
  // A triangulation of the loop alone (no new point) stays one: it gets the flips only.
  const int split_rounds = fill.points.empty() ? 0 : kSplitRounds;
  for (int round = 0;
       round < split_rounds && split_at_slivers(part.surface, fill_faces, kSliverAngle); ++round) {
    smooth_angles(part.surface, fill_faces, new_vertices);
    flip_to_max_min_angle(part.surface, fill_faces);
  }

  // Back to fill ids: the loop's vertices by their place in it, then the part's new vertices in
  // order (the fill's points, then those the splits added).
  std::map<VertexIndex, int> loop_index;
  for (size_t i = 0; i < fill.boundary.size(); ++i) {
    loop_index.emplace(vertex[i], static_cast<int>(i));
  }
  const auto fill_id = [&](VertexIndex v) {
    return static_cast<size_t>(v) < new_vertices
               ? loop_index.at(v)
               : static_cast<int>(fill.boundary.size() + (static_cast<size_t>(v) - new_vertices));
  };
  fill.points.clear();
  for (VertexIndex v : part.surface.vertices()) {
    if (static_cast<size_t>(v) < new_vertices) continue;
    const auto& p = part.surface.point(v);
    fill.points.emplace_back(p.x(), p.y(), p.z());
  }
  fill.triangles.clear();
  for (FaceIndex f : part.surface.faces()) {
    if (static_cast<size_t>(f) < fill_faces) continue;
    Triangle t;
    int k = 0;
    for (VertexIndex v : part.surface.vertices_around_face(part.surface.halfedge(f))) {
      t[k++] = fill_id(v);
    }
    fill.triangles.push_back(t);
  }
  if (original) fill.colors = colours_where_moved(mesh, *original, fill);
  return fill;
}

}  // namespace rangefill
