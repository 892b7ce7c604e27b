// A fill's smallest angles raised without changing its surface: Lawson's flips of its inner edges
// and CGAL's angle smoothing of its new points over the fill itself. Whatever made the fill (the
// faired patch, the image's grid stitched to the loop, the advancing front), its triangles along
// the loop meet short loop edges at long range; these steps, and points added where they are not
// enough, give them back angles over 10°.
#pragma once

#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"
#include "rangefill/hole/fill.h"

namespace rangefill {

/// `fill` (of a loop of `mesh`) with larger smallest angles: each inner edge of the fill is
/// flipped when that raises the smaller of its two triangles' smallest angles and the two
/// triangles bend by less than 60°, or when its triangles cross a face around the loop and the
/// flipped ones do not; the new points then move over the fill towards larger angles (CGAL's angle
/// smoothing, projected back onto the fill; no move makes an angle smaller or the surface
/// self-intersect), and the flips are made again. A triangle still under 12° gets a new point at
/// the middle of its longest inner edge, smoothed and flipped in turn (up to three rounds), unless
/// the fill has no new point (a triangulation of the loop alone stays one). The
/// loop and the points keep their order, added points come last; colours are interpolated where
/// points moved. A fill that does not join the faces around its loop as a manifold is returned as
/// it is: the caller's check refuses it.
Fill with_larger_angles(const Mesh& mesh, const MeshTopology& topology, Fill fill);

}  // namespace rangefill
