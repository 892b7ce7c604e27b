// Baselines the benchmark compares the back-ends with (Pérez et al., Section X-B): Liepa's hole
// filling as CGAL's Polygon Mesh Processing package implements it, with and without refinement
// and fairing.
#pragma once

#include <string>
#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/repair/pipeline.h"

namespace rangefill {

enum class Baseline {
  cgal_fair,         // triangulate_refine_and_fair_hole
  cgal_triangulate,  // triangulate_hole: the loop's vertices only (MeshLab's Close Holes does so)
};

struct BaselineOptions {
  Baseline method = Baseline::cgal_fair;
  std::vector<int> holes;                  // ids of the loops to fill (find_holes); empty = all
  double density_control_factor = 1.4142;  // cgal_fair: density of the refinement (CGAL: √2)
  int fairing_continuity = 1;              // cgal_fair: C0, C1 or C2 across the loop (CGAL: 1)
};

/// Fills boundary loops with CGAL::Polygon_mesh_processing, one after another in id order.
/// triangulate_hole is Liepa's minimum-weight triangulation of the loop (largest dihedral angle,
/// then area), searched among the faces of the 3D Delaunay triangulation of its vertices and,
/// failing that, among all triangles of them; CGAL's shortcut of a 2D triangulation for a nearly
/// planar loop is turned off, so that the result is Liepa's. triangulate_refine_and_fair_hole
/// refines that triangulation to the edge lengths around the loop and moves the new vertices to
/// minimise curvature variation (fair()); a loop whose fairing fails keeps its refined patch,
/// and its report's method says so.
///
/// The result reads like repair()'s: the input's vertices and faces come first, bit for bit; the
/// new ones follow, marked with the id of their loop (colours, when the mesh has them, from the
/// loop's vertices as boundary_colors gives them; normals from the new faces); one pass-0
/// HoleReport per loop asked for, `filled` when faces were added. Throws InvalidInput if a hole id
/// does not exist or the mesh is not an oriented 2-manifold (CGAL's Surface_mesh cannot hold it),
/// ProcessingError naming the loop if CGAL fails on one.
RepairResult fill_holes_cgal(const Mesh& mesh, const BaselineOptions& options);

/// "cgal-fair", "cgal-triangulate".
std::string baseline_name(Baseline baseline);
/// The baseline called `name`; throws InvalidInput otherwise, listing the names.
Baseline baseline_from_name(const std::string& name);

}  // namespace rangefill
