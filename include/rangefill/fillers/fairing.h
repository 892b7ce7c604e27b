// Refinement and fairing of a hole's patch: Liepa's triangulation of the loop refined to the edge
// lengths around it, its new vertices moved to minimise curvature variation (Liepa, "Filling
// holes in meshes", 2003, as CGAL's Polygon Mesh Processing implements it; the fairing's linear
// system is solved here, by LDL^T), then remeshed to the surroundings' mean edge length d_m and
// faired again.
#pragma once

#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"
#include "rangefill/hole/fill.h"
#include "rangefill/hole/holes.h"

namespace rangefill {

struct FairingOptions {
  int rings = 4;            // rings of faces around the loop that the fairing reads
  double density = 1.4142;  // CGAL's density_control_factor of the refinement (√2)
  int continuity = 2;       // C0, C1 or C2 across the loop (CGAL's default: 1)
  // Isotropic remeshing of the patch to edge length d_m, then faired again; 0: none. One round
  // does as well as three in less time; none leaves CGAL's refinement, with its longer edges.
  int remeshing_iterations = 1;
};

/// The faired patch of `hole` (a loop of `mesh`'s find_holes), its triangles oriented with the
/// surface, new points only inside. The mesh's faces within options.rings rings of the loop are
/// the patch's surroundings; its vertices and faces are not changed. `mean_edge` is d_m (> 0).
/// Refuses (Refusal::no_triangulation) a loop CGAL finds no triangulation for and
/// (Refusal::error) one whose fairing fails; the caller checks the fill against the mesh.
/// Throws InvalidInput on options out of range.
FillOutcome fill_by_fairing(const Mesh& mesh, const MeshTopology& topology,
                            const BoundaryLoop& hole, double mean_edge,
                            const FairingOptions& options);

}  // namespace rangefill
