// The core's translation unit of CGAL's hole filling and remeshing (heavy headers).
//
// CGAL's preconditions off in every build, as NDEBUG turns them off in Release: isotropic
// remeshing requires protected edges of at most 4/3 of the target length, and a hole's loop may
// have longer edges, which must stay whole (the input's faces are kept). CGAL then keeps them
// whole; with the check on (a build without NDEBUG) it aborts instead.
#define CGAL_NO_PRECONDITIONS
#include "rangefill/fillers/fairing.h"

#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <CGAL/Polygon_mesh_processing/refine.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Weights/cotangent_weights.h>

#include "core/cgal_surface_mesh.h"
#include "rangefill/core/errors.h"
#include "rangefill/fillers/loop_patch.h"

namespace rangefill {

namespace {

using namespace cgal_surface_mesh;
namespace pmp = CGAL::Polygon_mesh_processing;

// The C^k fairing of CGAL's fair() (Botsch et al., "On linear variational surface deformation
// methods", eq. 6): the inner vertices solve L^(k+1) x = 0, the others fixed, L = M^-1 K the
// Laplace-Beltrami operator of CGAL's cotangent weights (K) and Voronoi areas (M). Its rows
// scaled by M, the system is (K M^-1)^k K on the inner vertices: symmetric, so an LDL^T
// factorisation solves it, faster and in less memory than the LU factorisation of L^(k+1) in
// CGAL's fair(); the two solve the same system, so their solutions agree up to rounding. The
// system is a product of sparse matrices; CGAL expands each row over the paths of its
// (k+1)-ring, many weight look-ups and triplets per row at C2. Returns whether the system solved.
bool fair_inner_vertices(SurfaceMesh& surface, const std::vector<VertexIndex>& inner,
                         int continuity) {
  if (inner.empty()) return true;
  using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  const int vertex_ids = static_cast<int>(surface.num_vertices());  // removed ones included
  const int unknowns = static_cast<int>(inner.size());
  // The product reads K's rows and M on the vertices within k rings of the inner ones.
  std::vector<int> column(vertex_ids, -1);
  std::vector<char> reached(vertex_ids, 0);
  std::vector<VertexIndex> with_rows = inner;
  for (int i = 0; i < unknowns; ++i) {
    column[inner[i]] = i;
    reached[inner[i]] = 1;
  }
  size_t ring_begin = 0;
  for (int ring = 0; ring < continuity; ++ring) {
    const size_t ring_end = with_rows.size();
    for (size_t k = ring_begin; k < ring_end; ++k) {
      for (VertexIndex u : surface.vertices_around_target(surface.halfedge(with_rows[k]))) {
        if (!reached[u]) {
          reached[u] = 1;
          with_rows.push_back(u);
        }
      }
    }
    ring_begin = ring_end;
  }
  const CGAL::Weights::Secure_cotangent_weight_with_voronoi_area<SurfaceMesh> weights(
      surface, surface.points());
  Eigen::VectorXd inverse_area = Eigen::VectorXd::Zero(vertex_ids);  // M^-1
  std::vector<Eigen::Triplet<double>> entries;
  for (VertexIndex v : with_rows) {
    inverse_area[v] = weights.w_i(v);
    double sum = 0;
    for (auto h : surface.halfedges_around_target(surface.halfedge(v))) {
      // Of the edge, whichever half-edge asks: K stays symmetric to the last bit.
      const double w_ij = weights.w_ij(std::min(h, surface.opposite(h)));
      sum += w_ij;
      entries.emplace_back(v, surface.source(h), -w_ij);
    }
    entries.emplace_back(v, v, sum);
  }
  RowMatrix stiffness(vertex_ids, vertex_ids);  // K
  stiffness.setFromTriplets(entries.begin(), entries.end());
  RowMatrix rows(unknowns, vertex_ids);  // (K M^-1)^k K on the inner rows
  entries.clear();
  for (int i = 0; i < unknowns; ++i) entries.emplace_back(i, inner[i], 1.0);
  rows.setFromTriplets(entries.begin(), entries.end());
  rows = rows * stiffness;
  for (int power = 0; power < continuity; ++power) {
    rows = rows * inverse_area.asDiagonal() * stiffness;
  }

  // The fixed vertices' terms to the right-hand side.
  entries.clear();
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(unknowns, 3);
  for (int i = 0; i < unknowns; ++i) {
    for (RowMatrix::InnerIterator it(rows, i); it; ++it) {
      const VertexIndex v(static_cast<SurfaceMesh::size_type>(it.col()));
      if (column[v] >= 0) {
        entries.emplace_back(i, column[v], it.value());
      } else {
        const auto& p = surface.point(v);
        rhs.row(i) -= it.value() * Eigen::RowVector3d(p.x(), p.y(), p.z());
      }
    }
  }
  Eigen::SparseMatrix<double> system(unknowns, unknowns);
  system.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(system);
  if (solver.info() != Eigen::Success) return false;
  const Eigen::MatrixX3d solution = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !solution.allFinite()) return false;
  for (int i = 0; i < unknowns; ++i) {
    surface.point(inner[i]) = {solution(i, 0), solution(i, 1), solution(i, 2)};
  }
  return true;
}

// The loop's patch by Liepa's weight (triangulate_loop_liepa, as CGAL's triangulate_hole, whose
// result follows heap addresses), added to `surface` (a copy, left as it is when this fails);
// none when the loop has no such patch.
std::vector<FaceIndex> triangulate_loop(SurfaceMesh& surface, const MeshPart& part,
                                        const BoundaryLoop& hole) {
  const int n = static_cast<int>(hole.vertices.size());
  std::vector<VertexIndex> loop;
  std::vector<Vec3> positions, third_points;
  auto position = [&](VertexIndex v) {
    const auto& p = surface.point(v);
    return Vec3(p.x(), p.y(), p.z());
  };
  for (int v : hole.vertices) loop.push_back(part.local.at(v));
  for (int k = 0; k < n; ++k) {
    positions.push_back(position(loop[k]));
    // The face outside holds v_k → v_k+1; its third corner is where that half-edge's next ends.
    const auto along = surface.halfedge(loop[k], loop[(k + 1) % n]);
    if (along == SurfaceMesh::null_halfedge()) return {};
    third_points.push_back(position(surface.target(surface.next(along))));
  }
  std::set<std::pair<int, int>> chords;  // the surroundings' edges between loop vertices
  for (int i = 0; i < n; ++i) {
    for (int j = i + 2; j < n; ++j) {
      if (surface.halfedge(loop[i], loop[j]) != SurfaceMesh::null_halfedge()) chords.insert({i, j});
    }
  }
  std::vector<FaceIndex> faces;
  for (const Triangle& t : triangulate_loop_liepa(positions, third_points, chords)) {
    const FaceIndex face = surface.add_face(loop[t[0]], loop[t[1]], loop[t[2]]);
    if (face == SurfaceMesh::null_face()) return {};
    faces.push_back(face);
  }
  return faces;
}

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
  return fair_inner_vertices(surface, inner, options.continuity);
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
      surroundings(mesh, faces_within_rings(mesh, topology, hole.vertices, options.rings));
  if (!part) return Refused{Refusal::not_manifold, "its surroundings are not a 2-manifold"};
  SurfaceMesh& surface = part->surface;
  const size_t original_faces = surface.number_of_faces();
  // The loop runs along the faces (v_k, v_k+1); its border half-edge runs from v_k+1 to v_k.
  const auto border =
      surface.halfedge(part->local.at(hole.vertices[1]), part->local.at(hole.vertices[0]));
  if (border == SurfaceMesh::null_halfedge() || !surface.is_border(border)) {
    return Refused{Refusal::not_manifold, "its loop is not a border of its surroundings"};
  }
  std::vector<FaceIndex> faces = triangulate_loop(surface, *part, hole);
  std::vector<VertexIndex> vertices;
  pmp::refine(surface, std::vector<FaceIndex>(faces), std::back_inserter(faces),
              std::back_inserter(vertices),
              CGAL::parameters::density_control_factor(options.density));
  if (faces.empty()) return Refused{Refusal::no_triangulation, ""};
  if (!fair_inner_vertices(surface, vertices, options.continuity))
    return Refused{Refusal::error, "the fairing's linear system has no solution"};
  if (options.remeshing_iterations > 0 &&
      !remesh_and_fair(surface, original_faces, part->global.size(), mean_edge, options)) {
    return Refused{Refusal::error, "the fairing of the remeshed patch has no solution"};
  }
  return patch_as_fill(surface, original_faces, part->global, hole);
}

}  // namespace rangefill
