// The core's translation unit of CGAL's hole filling and remeshing (heavy headers).
//
// CGAL's preconditions off in every build, as NDEBUG turns them off in Release: isotropic
// remeshing requires protected edges of at most 4/3 of the target length, and a hole's loop may
// have longer edges, which must stay whole (the input's faces are kept). CGAL then keeps them
// whole; with the check on (a build without NDEBUG) it aborts instead.
#define CGAL_NO_PRECONDITIONS
#include "rangefill/repair/fairing.h"

#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <vector>

#include <CGAL/Polygon_mesh_processing/fair.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include "rangefill/core/errors.h"
#include "repair/cgal_surface_mesh.h"

namespace rangefill {

namespace {

using namespace cgal_surface_mesh;
namespace pmp = CGAL::Polygon_mesh_processing;

// CGAL's weights for fairing (cotangents, Voronoi areas), each computed once, when first asked:
// a row of the C2 system (L³ at a vertex) asks for the weights of its vertex's third ring some
// 300 times over, and their computation was most of a fairing. The same numbers, faster. A copy
// per fairing (CGAL copies it), so the weights are of that fairing's mesh.
class FairingWeights {
 public:
  explicit FairingWeights(const SurfaceMesh& surface) : surface_(&surface) {}

  double w_i(VertexIndex v) const {
    return cached(vertex_weights_, v, [&] { return weights().w_i(v); });
  }
  double w_ij(SurfaceMesh::Halfedge_index h) const {
    return cached(halfedge_weights_, h, [&] { return weights().w_ij(h); });
  }

 private:
  using Weights = CGAL::Weights::Secure_cotangent_weight_with_voronoi_area<SurfaceMesh>;

  Weights weights() const { return Weights(*surface_, surface_->points()); }

  template <typename Index, typename Compute>
  static double cached(std::vector<double>& cache, Index index, Compute compute) {
    const size_t i = static_cast<size_t>(index);
    if (i >= cache.size()) cache.resize(i + 1, std::numeric_limits<double>::quiet_NaN());
    if (std::isnan(cache[i])) cache[i] = compute();
    return cache[i];
  }

  const SurfaceMesh* surface_;
  mutable std::vector<double> vertex_weights_, halfedge_weights_;
};

// The surroundings as a mesh part; nullopt when they do not form an oriented 2-manifold (the hole
// is then not a CGAL border).
std::optional<MeshPart> surroundings(const Mesh& mesh, const std::vector<int>& faces) {
  MeshPart part;
  for (int face : faces) {
    if (!part.add_face(mesh, face)) return std::nullopt;
  }
  return part;
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
      CGAL::parameters::fairing_continuity(static_cast<unsigned int>(options.continuity))
          .weight_calculator(FairingWeights(surface)));
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
  std::optional<MeshPart> part =
      surroundings(mesh, faces_around(topology, mesh, hole.vertices, options.rings));
  if (!part) return Refused{Refusal::not_manifold, "its surroundings are not a 2-manifold"};
  SurfaceMesh& surface = part->surface;
  const size_t original_faces = surface.number_of_faces();
  // The loop runs along the faces (v_k, v_k+1); its border half-edge runs from v_k+1 to v_k.
  const auto border =
      surface.halfedge(part->local.at(hole.vertices[1]), part->local.at(hole.vertices[0]));
  if (border == SurfaceMesh::null_halfedge() || !surface.is_border(border)) {
    return Refused{Refusal::not_manifold, "its loop is not a border of its surroundings"};
  }
  std::vector<FaceIndex> faces;
  std::vector<VertexIndex> vertices;
  const bool faired = std::get<0>(pmp::triangulate_refine_and_fair_hole(
      surface, border, std::back_inserter(faces), std::back_inserter(vertices),
      CGAL::parameters::use_2d_constrained_delaunay_triangulation(false)
          .density_control_factor(options.density)
          .fairing_continuity(static_cast<unsigned int>(options.continuity))
          .weight_calculator(FairingWeights(surface))));
  if (faces.empty()) return Refused{Refusal::no_triangulation, ""};
  if (!faired) return Refused{Refusal::error, "the fairing's linear system has no solution"};
  if (options.remeshing_iterations > 0 &&
      !remesh_and_fair(surface, original_faces, part->global.size(), mean_edge, options)) {
    return Refused{Refusal::error, "the fairing of the remeshed patch has no solution"};
  }
  return patch_as_fill(surface, original_faces, part->global, hole);
}

}  // namespace rangefill
