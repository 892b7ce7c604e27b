// The zone of interest around a hole (Pérez et al., Section V): rings of faces grown out from the
// hole boundary with normal diffusion, so that folds and sharp turns are not swallowed.
#pragma once

#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"
#include "rangefill/hole/holes.h"

namespace rangefill {

struct ZoneOptions {
  double gamma_degrees = 75;  // γ of eq. 4: a candidate normal further than this from the search
                              // vertex's diffused normal rejects its triangle
  double alpha = 3;           // α of eq. 5: weight of the search vertex normal
  double kappa = 0.15;        // κ of eq. 2: wanted ratio of hole to valid pixels
  int rings = 0;              // ν; 0 = from eq. 2, clamped to [min_rings, max_rings]
  int min_rings = 3;
  int max_rings = 40;
};

struct Zone {
  std::vector<int> faces;        // ascending
  std::vector<int> vertices;     // ascending, every vertex of `faces`
  int rings = 0;                 // ν used
  int rings_grown = 0;           // rings that added at least one face (≤ rings)
  std::vector<int> other_holes;  // ids of other boundary loops that the zone reaches
  int rejected_faces = 0;        // candidate triangles refused by eq. 4
};

/// ν of eq. 2 for a hole of (projected) area A: ν = A / (d_m (0.106 κ A + 18)), evaluated with
/// lengths in units of d_m (A → A / d_m², d_m → 1) so that it does not depend on the model's scale;
/// the paper's constants were fitted in millimetres on scans with d_m of 0.1–0.34 mm.
int rings_for_hole(double hole_area, double mean_edge, const ZoneOptions& options);

/// Grows the zone of `hole` (Section V). Starting from the boundary vertices as search vertices,
/// each ring considers the faces not yet in the zone that touch a search vertex, in ascending
/// order; a face is rejected when the angle (eq. 4) between the diffused normal of one of its
/// search vertices and the normal of one of its new vertices exceeds γ; the new vertices of an
/// accepted face take the diffused normal n' = (n + α·ν_i·n_s) / 2 (eq. 5, n_s the sum of its
/// search vertices' diffused normals, normalised) and become the next ring's search vertices.
/// Faces whose three vertices are already in the zone are added at the end. The starting normals
/// N are vertex_normal's (topology.h), computed for the vertices the zone reaches only.
/// Precondition: `hole` belongs to `holes`.
Zone grow_zone(const Mesh& mesh, const MeshTopology& topology, const HoleSet& holes,
               const BoundaryLoop& hole, double mean_edge, const ZoneOptions& options = {});

}  // namespace rangefill
