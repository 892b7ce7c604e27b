// The core's translation unit of CGAL's hole filling and remeshing (heavy headers).
//
// CGAL's preconditions off in every build, as NDEBUG turns them off in Release: isotropic
// remeshing requires protected edges of at most 4/3 of the target length, and a hole's loop may
// have longer edges, which must stay whole (the input's faces are kept). CGAL then keeps them
// whole; with the check on (a build without NDEBUG) it aborts instead.
#define CGAL_NO_PRECONDITIONS
#include "rangefill/repair/fairing.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <set>

#include <CGAL/Polygon_mesh_processing/fair.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include "rangefill/core/errors.h"
#include "repair/cgal_surface_mesh.h"

namespace rangefill {

namespace {

using namespace cgal_surface_mesh;
namespace pmp = CGAL::Polygon_mesh_processing;

// The faces within `rings` rings of the loop's vertices, ascending.
std::vector<int> faces_around(const MeshTopology& topology, const Mesh& mesh,
                              const BoundaryLoop& hole, int rings) {
  std::set<int> vertices(hole.vertices.begin(), hole.vertices.end()), faces;
  for (int ring = 0; ring < rings; ++ring) {
    std::set<int> reached;
    for (int v : vertices) {
      for (int k = topology.faces_of_vertex_begin(v); k < topology.faces_of_vertex_end(v); ++k) {
        const int face = topology.vertex_faces[k];
        if (faces.insert(face).second) {
          for (int corner : mesh.triangles[face]) reached.insert(corner);
        }
      }
    }
    vertices = std::move(reached);
  }
  return {faces.begin(), faces.end()};
}

// The surroundings as a Surface_mesh; `local` maps mesh vertex ids to its vertices, `global`
// back. Nullopt when they do not form an oriented 2-manifold (the hole is then not a CGAL border).
std::optional<SurfaceMesh> surroundings(const Mesh& mesh, const std::vector<int>& faces,
                                        std::map<int, VertexIndex>& local,
                                        std::vector<int>& global) {
  SurfaceMesh surface;
  for (int face : faces) {
    std::array<VertexIndex, 3> corners;
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles[face][k];
      auto [entry, added] = local.emplace(v, VertexIndex());
      if (added) {
        const Vec3& p = mesh.positions[v];
        entry->second = surface.add_vertex({p.x(), p.y(), p.z()});
        global.push_back(v);
      }
      corners[k] = entry->second;
    }
    if (surface.add_face(corners[0], corners[1], corners[2]) == SurfaceMesh::null_face()) {
      return std::nullopt;
    }
  }
  return surface;
}

// The patch (faces not among the first `original_faces`) as a Fill of `hole`.
FillOutcome patch_as_fill(const SurfaceMesh& surface, size_t original_faces,
                          const std::vector<int>& global, const BoundaryLoop& hole) {
  std::map<int, int> boundary_index;
  for (size_t i = 0; i < hole.vertices.size(); ++i) {
    boundary_index.emplace(hole.vertices[i], static_cast<int>(i));
  }
  Fill fill;
  fill.boundary = hole.vertices;
  std::map<VertexIndex, int> fill_index;
  for (FaceIndex f : surface.faces()) {
    if (static_cast<size_t>(f) < original_faces) continue;
    Triangle t;
    int k = 0;
    for (VertexIndex v : surface.vertices_around_face(surface.halfedge(f))) {
      auto [entry, added] = fill_index.emplace(v, 0);
      if (added) {
        if (static_cast<size_t>(v) < global.size()) {
          const auto on_loop = boundary_index.find(global[v]);
          if (on_loop == boundary_index.end()) {
            return Refused{Refusal::not_manifold, "the patch uses a vertex off the loop"};
          }
          entry->second = on_loop->second;
        } else {
          const auto& p = surface.point(v);
          entry->second = static_cast<int>(hole.vertices.size() + fill.points.size());
          fill.points.emplace_back(p.x(), p.y(), p.z());
        }
      }
      t[k++] = entry->second;
    }
    fill.triangles.push_back(t);
  }
  return fill;
}

// Remeshes the patch (faces from `original_faces` on) to edge length `target`, its border kept,
// then fairs its inner vertices again. Returns whether the fairing succeeded.
bool remesh_and_fair(SurfaceMesh& surface, size_t original_faces, size_t original_vertices,
                     double target, const FairingOptions& options) {
  std::vector<FaceIndex> patch;
  for (FaceIndex f : surface.faces()) {
    if (static_cast<size_t>(f) >= original_faces) patch.push_back(f);
  }
  // The loop's edges border the patch, so they are kept whole (protect_constraints; see the top
  // of this file for CGAL's precondition on their length).
  pmp::isotropic_remeshing(patch, target, surface,
                           CGAL::parameters::number_of_iterations(
                               static_cast<unsigned int>(options.remeshing_iterations))
                               .protect_constraints(true));
  std::vector<VertexIndex> inner;
  for (VertexIndex v : surface.vertices()) {
    if (static_cast<size_t>(v) >= original_vertices) inner.push_back(v);
  }
  return pmp::fair(
      surface, inner,
      CGAL::parameters::fairing_continuity(static_cast<unsigned int>(options.continuity)));
}

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

// Lawson's flips inside the patch (faces from `original_faces` on): an inner edge is flipped when
// that raises the smaller of the two triangles' smallest angles, the two faces bend by less than
// 60° (the surface keeps its shape) and the new edge does not exist yet. Slivers that remeshing
// leaves along the loop (an ear over two nearly collinear loop edges) go this way.
void flip_to_max_min_angle(SurfaceMesh& surface, size_t original_faces) {
  const auto in_patch = [&](FaceIndex f) {
    return f != SurfaceMesh::null_face() && static_cast<size_t>(f) >= original_faces;
  };
  constexpr double kMinBendCosine = 0.5;
  for (int sweep = 0; sweep < 10; ++sweep) {
    bool flipped = false;
    for (auto edge : surface.edges()) {
      const auto h = surface.halfedge(edge), o = surface.opposite(h);
      if (!in_patch(surface.face(h)) || !in_patch(surface.face(o))) continue;
      const VertexIndex a = surface.source(h), b = surface.target(h);
      const VertexIndex c = surface.target(surface.next(h)), d = surface.target(surface.next(o));
      if (surface.halfedge(c, d) != SurfaceMesh::null_halfedge()) continue;
      const auto &pa = surface.point(a), &pb = surface.point(b);
      const auto &pc = surface.point(c), &pd = surface.point(d);
      // Faces (a, b, c) and (b, a, d) become (a, d, c) and (d, b, c).
      const double before = std::min(smallest_angle(pa, pb, pc), smallest_angle(pb, pa, pd));
      const double after = std::min(smallest_angle(pa, pd, pc), smallest_angle(pd, pb, pc));
      if (after <= before + 1e-9) continue;
      const auto n1 = CGAL::unit_normal(pa, pb, pc), n2 = CGAL::unit_normal(pb, pa, pd);
      if (n1 * n2 < kMinBendCosine) continue;
      const auto m1 = CGAL::normal(pa, pd, pc), m2 = CGAL::normal(pd, pb, pc);
      if (m1 * n1 <= 0 || m1 * n2 <= 0 || m2 * n1 <= 0 || m2 * n2 <= 0) continue;
      CGAL::Euler::flip_edge(h, surface);
      flipped = true;
    }
    if (!flipped) break;
  }
}

}  // namespace

FillOutcome fill_by_fairing(const Mesh& mesh, const MeshTopology& topology,
                            const BoundaryLoop& hole, double mean_edge,
                            const FairingOptions& options) {
  if (options.rings < 1 || !(options.density > 0) || options.continuity < 0 ||
      options.continuity > 2 || options.remeshing_iterations < 0 || !(mean_edge > 0)) {
    throw InvalidInput(
        "fairing: rings ≥ 1, density > 0, continuity 0, 1 or 2, remeshing iterations ≥ 0 and "
        "d_m > 0 expected");
  }
  if (hole.vertices.size() < 3) return Refused{Refusal::no_triangulation, ""};
  std::map<int, VertexIndex> local;
  std::vector<int> global;
  std::optional<SurfaceMesh> surface =
      surroundings(mesh, faces_around(topology, mesh, hole, options.rings), local, global);
  if (!surface) return Refused{Refusal::not_manifold, "its surroundings are not a 2-manifold"};
  const size_t original_faces = surface->number_of_faces();
  // The loop runs along the faces (v_k, v_k+1); its border half-edge runs from v_k+1 to v_k.
  const auto border = surface->halfedge(local.at(hole.vertices[1]), local.at(hole.vertices[0]));
  if (border == SurfaceMesh::null_halfedge() || !surface->is_border(border)) {
    return Refused{Refusal::not_manifold, "its loop is not a border of its surroundings"};
  }
  std::vector<FaceIndex> faces;
  std::vector<VertexIndex> vertices;
  const bool faired = std::get<0>(pmp::triangulate_refine_and_fair_hole(
      *surface, border, std::back_inserter(faces), std::back_inserter(vertices),
      CGAL::parameters::use_2d_constrained_delaunay_triangulation(false)
          .density_control_factor(options.density)
          .fairing_continuity(static_cast<unsigned int>(options.continuity))));
  if (faces.empty()) return Refused{Refusal::no_triangulation, ""};
  if (!faired) return Refused{Refusal::error, "the fairing's linear system has no solution"};
  if (options.remeshing_iterations > 0 &&
      !remesh_and_fair(*surface, original_faces, global.size(), mean_edge, options)) {
    return Refused{Refusal::error, "the fairing of the remeshed patch has no solution"};
  }
  flip_to_max_min_angle(*surface, original_faces);
  return patch_as_fill(*surface, original_faces, global, hole);
}

}  // namespace rangefill
