// What every way of filling a hole gives: a fill, or a refusal saying why there is none.
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"

namespace rangefill {

/// A hole's fill before it joins the mesh. Fill vertex i < boundary.size() is mesh vertex
/// boundary[i]; fill vertex boundary.size() + k is the new point points[k].
struct Fill {
  std::vector<int> boundary;
  std::vector<Vec3> points;
  std::vector<Triangle> triangles;
  std::vector<Rgb> colors;  // of the points, when they were restored with the geometry; else empty
};

/// Why a hole was not filled, by a filler (filler.h) or at all.
enum class Refusal {
  nonmanifold_rim,   // the loop passes one of the input's unfillable_vertices (topology.h)
  empty_zone,        // the zone of interest has no face (Section V)
  no_plane,          // no plane sees the rim from the front with a simple boundary (VI-C)
  partial_view,      // the image sees less of the hole's surroundings than min_rim_support
  not_manifold,      // the fill would not join the mesh as a manifold (stitching, validation)
  intersects,        // the fill would intersect the surface or itself
  front_stuck,       // the advancing front did not close
  no_part,           // no part of a complex hole could be filled (VI-C)
  no_triangulation,  // the loop has no triangulation without new vertices
  border_sized,      // a loop too large for the faired patch: a border (holes.h) or > 3000 d_m²
  error,             // a stage failed (ProcessingError), its message in the detail
};

/// The refusal in words, e.g. "the fill would intersect the surface or itself".
std::string refusal_text(Refusal refusal);

/// The enumerator's name, for machine-readable reports: "intersects", "front_stuck", ...
std::string refusal_name(Refusal refusal);

/// A refusal and what it is about (one line; may be empty).
struct Refused {
  Refusal refusal = Refusal::error;
  std::string detail;
};

/// A fill, or why there is none.
using FillOutcome = std::variant<Fill, Refused>;

/// Why `fill` would not join the mesh as a manifold, or nullopt when it would: each boundary edge
/// used exactly once, reversed; every other edge used twice in opposite directions; no chord
/// between boundary vertices that the mesh already has as an edge; no triangle of zero area, nor,
/// given a `viewer` direction, one facing away from it.
std::optional<std::string> fill_defect(const Mesh& mesh, const MeshTopology& topology,
                                       const Fill& fill, const Vec3* viewer = nullptr);

/// Whether two fills of holes of `mesh` intersect beyond the mesh vertices they share (exact
/// predicates, core/intersection.h). Fills of one pass are each checked against the mesh, not
/// against each other: this is that check.
bool fills_intersect(const Mesh& mesh, const Fill& a, const Fill& b);

}  // namespace rangefill
