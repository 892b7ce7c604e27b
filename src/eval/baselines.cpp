// CGAL's hole filling with refinement and fairing (heavy headers: the one such translation unit of
// the evaluation library; repair/loop_patch.cpp and repair/fairing.cpp are the core's).
#include "rangefill/eval/baselines.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <map>

#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include "core/cgal_surface_mesh.h"
#include "rangefill/core/errors.h"
#include "rangefill/core/topology.h"
#include "rangefill/hole/holes.h"

namespace rangefill {

namespace {

using namespace cgal_surface_mesh;
namespace pmp = CGAL::Polygon_mesh_processing;

SurfaceMesh to_surface_mesh(const Mesh& mesh) {
  SurfaceMesh surface;
  surface.reserve(mesh.vertex_count(), 3 * mesh.face_count() / 2 + mesh.vertex_count(),
                  mesh.face_count());
  for (const Vec3& p : mesh.positions) surface.add_vertex({p.x(), p.y(), p.z()});
  for (int f = 0; f < mesh.face_count(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (surface.add_face(VertexIndex(t[0]), VertexIndex(t[1]), VertexIndex(t[2])) ==
        SurfaceMesh::null_face()) {
      throw InvalidInput("cgal baseline: face " + std::to_string(f) +
                         " makes the mesh non-manifold or misoriented");
    }
  }
  return surface;
}

// Fills one loop; returns whether fairing (when asked) succeeded.
bool fill_loop(SurfaceMesh& surface, const BoundaryLoop& loop, const BaselineOptions& options,
               std::vector<FaceIndex>& faces, std::vector<VertexIndex>& vertices) {
  // The loop runs along the faces (v_k, v_k+1); its border half-edge runs from v_k+1 to v_k.
  const auto border =
      surface.halfedge(VertexIndex(loop.vertices[1]), VertexIndex(loop.vertices[0]));
  if (border == SurfaceMesh::null_halfedge() || !surface.is_border(border)) {
    throw ProcessingError("cgal baseline: hole " + std::to_string(loop.id) +
                          ": its loop is not a border of the mesh");
  }
  const auto parameters = CGAL::parameters::use_2d_constrained_delaunay_triangulation(false);
  if (options.method == Baseline::cgal_triangulate) {
    pmp::triangulate_hole(surface, border, std::back_inserter(faces), parameters);
    return true;
  }
  return std::get<0>(pmp::triangulate_refine_and_fair_hole(
      surface, border, std::back_inserter(faces), std::back_inserter(vertices),
      parameters.density_control_factor(options.density_control_factor)
          .fairing_continuity(static_cast<unsigned int>(options.fairing_continuity))));
}

}  // namespace

std::string baseline_name(Baseline baseline) {
  return baseline == Baseline::cgal_fair ? "cgal-fair" : "cgal-triangulate";
}

Baseline baseline_from_name(const std::string& name) {
  if (name == "cgal-fair") return Baseline::cgal_fair;
  if (name == "cgal-triangulate") return Baseline::cgal_triangulate;
  throw InvalidInput("unknown baseline '" + name + "' (expected cgal-fair or cgal-triangulate)");
}

namespace {

// Appends CGAL's patch of `loop` (its new `vertices` and `faces` in `surface`) to `mesh` with
// provenance `id`: Surface_mesh appends, so the new vertices and faces are the last ones, in
// creation order. Returns the vertices added.
int copy_patch(const SurfaceMesh& surface, std::vector<VertexIndex> vertices,
               std::vector<FaceIndex> faces, const BoundaryLoop& loop, int id,
               const std::string& name, Mesh& mesh) {
  std::sort(vertices.begin(), vertices.end());
  std::sort(faces.begin(), faces.end());
  const int first_vertex = mesh.vertex_count();
  std::vector<Vec3> points;
  for (VertexIndex v : vertices) {
    const Kernel::Point_3& p = surface.point(v);
    points.emplace_back(p.x(), p.y(), p.z());
  }
  const std::vector<Rgb> colors = mesh.has_colors() ? boundary_colors(mesh, loop.vertices, points)
                                                    : std::vector<Rgb>(points.size(), Rgb::Zero());
  for (size_t i = 0; i < points.size(); ++i) add_vertex(mesh, points[i], id, colors[i]);
  for (FaceIndex f : faces) {
    Triangle t;
    int k = 0;
    for (VertexIndex v : surface.vertices_around_face(surface.halfedge(f))) {
      const auto found = std::lower_bound(vertices.begin(), vertices.end(), v);
      if (found != vertices.end() && *found == v) {
        t[k++] = first_vertex + static_cast<int>(found - vertices.begin());
      } else if (static_cast<int>(v) < first_vertex) {
        t[k++] = static_cast<int>(v);
      } else {
        throw ProcessingError(name + ": hole " + std::to_string(id) +
                              ": a new face uses a vertex CGAL did not report");
      }
    }
    add_face(mesh, t, id);
  }
  return static_cast<int>(points.size());
}

// The loops of the result: each an input loop, not selected or whose fill failed.
std::vector<OpenLoop> open_input_loops(const Mesh& result, const HoleSet& input,
                                       const std::vector<int>& selected) {
  std::map<std::vector<int>, int> input_loop;
  for (const BoundaryLoop& loop : input.loops) input_loop.emplace(sorted_vertices(loop), loop.id);
  std::vector<OpenLoop> open;
  for (const BoundaryLoop& loop : find_holes(result, build_topology(result)).loops) {
    const int id = input_loop.at(sorted_vertices(loop));
    const bool was_selected = std::binary_search(selected.begin(), selected.end(), id);
    open.push_back({loop.id, id, static_cast<int>(loop.vertices.size()), loop.area, loop.area_share,
                    was_selected ? OpenReason::failed : OpenReason::not_selected});
  }
  return open;
}

}  // namespace

RepairResult fill_holes_cgal(const Mesh& mesh, const BaselineOptions& options) {
  if (options.fairing_continuity < 0 || options.fairing_continuity > 2) {
    throw InvalidInput("cgal baseline: fairing continuity must be 0, 1 or 2");
  }
  if (!(options.density_control_factor > 0)) {
    throw InvalidInput("cgal baseline: the density control factor must be positive");
  }
  const MeshTopology topology = build_topology(mesh);
  const HoleSet loops = find_holes(mesh, topology);
  std::vector<int> selected = options.holes;
  if (selected.empty()) {
    for (const BoundaryLoop& loop : loops.loops) selected.push_back(loop.id);
  }
  std::sort(selected.begin(), selected.end());
  for (int id : selected) {
    if (id < 0 || id >= static_cast<int>(loops.loops.size())) {
      throw InvalidInput("cgal baseline: there is no boundary loop " + std::to_string(id));
    }
  }
  SurfaceMesh surface = to_surface_mesh(mesh);
  const std::string name = baseline_name(options.method);

  RepairResult result;
  result.mesh = mesh;
  result.restoration_matrix.push_back(
      {mesh.vertex_count(), topology.edge_count, mesh.face_count()});
  for (int id : selected) {
    const BoundaryLoop& loop = loops.loops[id];
    HoleReport report;
    report.id = report.loop = id;
    report.boundary_vertices = static_cast<int>(loop.vertices.size());
    report.area = loop.area;
    report.method = name;
    std::vector<FaceIndex> faces;
    std::vector<VertexIndex> vertices;
    const auto start = std::chrono::steady_clock::now();
    bool faired = true;
    try {
      faired = fill_loop(surface, loop, options, faces, vertices);
    } catch (const Error&) {
      throw;
    } catch (const std::exception& error) {
      throw ProcessingError(name + ": hole " + std::to_string(id) + ": " + error.what());
    }
    report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const int new_vertices = copy_patch(surface, vertices, faces, loop, id, name, result.mesh);
    report.new_vertices = new_vertices;
    report.new_faces = static_cast<int>(faces.size());
    report.filled = !faces.empty();
    if (!report.filled) report.failure = name + ": no triangulation of the loop found";
    if (report.filled && !faired) report.method += " (fairing failed: refined only)";
    if (report.filled) {
      // Each new edge has two new faces but for the loop's edges, which had one already.
      result.restoration_matrix.push_back({report.new_vertices,
                                           (3LL * report.new_faces - report.boundary_vertices) / 2,
                                           report.new_faces});
    }
    result.holes.push_back(std::move(report));
  }
  result.open_loops = open_input_loops(result.mesh, loops, selected);
  if (result.mesh.has_normals()) {
    const std::vector<Vec3> normals = vertex_normals_from_faces(result.mesh);
    std::copy(normals.begin() + mesh.vertex_count(), normals.end(),
              result.mesh.normals.begin() + mesh.vertex_count());
  }
  return result;
}

}  // namespace rangefill
