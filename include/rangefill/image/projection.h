// The projection plane of a hole (Pérez et al., Section VI, Fig. 8): the orientation that maximises
// the projected area of the zone, with a hole boundary that projects without self-intersection.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "rangefill/core/geometry2d.h"
#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"
#include "rangefill/hole/holes.h"
#include "rangefill/hole/zone.h"

namespace rangefill {

/// A rigid frame Σ' attached to a projection plane: local z is the viewing direction (towards the
/// viewer, so the zone's faces are seen from their front), local x, y span the image plane.
struct Frame {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // rows: the local axes in world space
  Vec3 origin = Vec3::Zero();

  Vec3 to_local(const Vec3& p) const { return rotation * (p - origin); }
  Vec3 to_world(const Vec3& q) const { return rotation.transpose() * q + origin; }
  Vec3 normal() const { return rotation.row(2).transpose(); }
};

struct ProjectionOptions {
  int search_directions = 256;     // directions sampled on the cap around the start
  double search_cap_degrees = 80;  // half-angle of that cap
  int refinements = 3;             // each halves the cap around the best direction so far
  int max_orientations = 64;       // candidates checked before the hole is declared complex
  double max_rim_behind = 0.1;     // area fraction of the faces on the hole boundary that may be
                                   // seen from behind (a jagged rim has a few steep slivers)
  int planes = 3;                  // acceptable planes returned, best first
  double min_separation_degrees = 10;  // between two returned planes
};

/// A hole seen from a projection plane: the frame and the loop's vertices in its image plane,
/// computed once per plane and read by every later stage on it (the range image, back-projection,
/// stitching, the parts of a complex hole).
struct HoleInPlane {
  Frame frame;
  std::vector<Vec2> loop;  // the loop's vertices in the frame's x, y, in loop order
};

/// `hole` seen from `frame`.
HoleInPlane hole_in_plane(const Mesh& mesh, const BoundaryLoop& hole, const Frame& frame);

struct Projection {
  HoleInPlane plane;
  double projected_area = 0;  // Σ max(0, n·a_f) over the zone's faces (a_f: area vectors)
  double folded_area = 0;     // Σ max(0, −n·a_f): zone area seen from behind
};

struct ProjectionSearch {
  std::vector<Projection> planes;  // acceptable planes, best first; empty: a complex hole
  int orientations_tried = 0;      // candidates checked against the conditions, best first
  HoleInPlane best;                // along the best-scoring direction, acceptable or not
};

/// Chooses planes (Section VI, Fig. 8). Candidates: the area-weighted normal of the zone, the
/// hole's own vector area, the smallest principal axis of the zone's vertices (PCA), and directions
/// sampled on caps around the best of them, scored by projected minus twice the folded area
/// (n·Σa_f − folded). A candidate is acceptable when the faces on the hole boundary face the viewer
/// (up to max_rim_behind of their area) and the boundary projects as a simple polygon; the best
/// `planes` acceptable ones at least min_separation_degrees apart are returned, so that a later
/// stage can fall back on the next. Faces of the zone seen from behind are left to visible_part().
/// In a frame, local x is the main axis of the projected zone (a tight image), the origin the
/// centroid of the boundary.
ProjectionSearch find_projections(const Mesh& mesh, const MeshTopology& topology, const Zone& zone,
                                  const BoundaryLoop& hole, const ProjectionOptions& options = {});

/// The part of the zone that the frame sees without fold-over: its faces that face the viewer and
/// are connected through shared edges, across such faces only, to the faces on the hole boundary.
/// Folds further out (a zone wrapping round a limb) are cut off instead of failing the hole.
Zone visible_part(const Mesh& mesh, const MeshTopology& topology, const Zone& zone,
                  const BoundaryLoop& hole, const Frame& frame);

/// True if the closed polygon (consecutive points joined, last to first) has no two non-adjacent
/// edges that touch or cross and no repeated point.
bool is_simple_polygon(const std::vector<Vec2>& polygon);

}  // namespace rangefill
