// Advancing-front hole filling with MLS-projected points (Tekumalla & Cohen, Section 3), for holes
// that no projection plane can unfold: it works locally, closing the hole from its boundary
// inwards.
#pragma once

#include <vector>

#include "rangefill/core/intersection.h"
#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"
#include "rangefill/fillers/mls.h"
#include "rangefill/hole/fill.h"
#include "rangefill/hole/holes.h"

namespace rangefill {

struct FrontOptions {
  double phi = 5 * M_PI / 9;  // make-convex joins adjacent front edges whose hole angle is below φ
  double shrink = 0.8;  // d_e and φ are multiplied by this when an iteration makes no progress
  int max_stalls = 6;   // ... at most this many times in a row; then the front is closed
  // A front that has not become shorter than (1 − min_shrinkage) × its shortest length for
  // `patience` iterations extrudes the surface (round a thin tube's end) instead of closing it.
  int patience = 3;
  double min_shrinkage = 0.02;
  double search_radius = 3;  // front edges within this many a of a candidate are checked, in the
                             // local MLS plane, for crossings
};

/// Fills `hole` by alternating make-convex (join adjacent front edges whose angle is below φ when
/// the new edge crosses no other front edge in the local MLS parameterisation) and add-vertices
/// (for each front edge of length e, a point on its perpendicular bisector at
/// d_e = √(4a² − e²)/2 towards the hole, a the mean boundary edge length, projected onto `surface`,
/// kept when its triangle crosses no front edge), until three vertices remain and one triangle
/// closes the hole. A front that stalls or stops getting shorter is closed at once by
/// triangulate_loop_least_area (Liepa's triangulation, as CGAL implements it). Each pass's new
/// points join `surface`'s samples, so that the surface the front projects onto grows with it.
/// Samples facing away from the front (the other side of a thin part) are ignored. Refused
/// (front_stuck) when the front grows past ten times a flat disk's triangles or its last vertices
/// cannot be closed. Throws InvalidInput when the hole has fewer than 3 vertices.
FillOutcome fill_by_front(const Mesh& mesh, const MeshTopology& topology,
                          const IntersectionIndex& faces, const BoundaryLoop& hole,
                          MlsSurface surface, const FrontOptions& options = {});

}  // namespace rangefill
