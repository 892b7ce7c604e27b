// Holes punched by the mesh evaluation kit's `punch` (its output directory: holed.ply, one
// gt_hole_<id>.ply per hole with the removed faces, holes.json), read back so that `rangefill
// bench --punched` scores the very holes the kit scores.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/eval/punch.h"

namespace rangefill::cli {

struct KitPunch {
  Mesh original;         // holed.ply with each hole's removed faces appended: a closed mesh
  PunchResult punched;   // its mesh is holed.ply as read, vertex for vertex and face for face
  double mean_edge = 0;  // the kit's d_m (holes.json), the unit of its scores
};

/// Reads the kit's punch directory `dir`. Each hole takes the kit's curvature class, its
/// on_feature flag as sharp_feature, its curvature measure as bending, its radius (world units)
/// and shape (an elongated hole is an ellipse there, with length 0 here). Throws InvalidInput
/// naming the file when a file is missing or malformed, or when a removed face's corner is neither
/// a vertex of holed.ply nor a removed vertex of that hole.
KitPunch read_kit_punch(const std::filesystem::path& dir);

/// The kit punch directories at or under each of `arguments` (those holding a holes.json),
/// sorted; throws UsageError for an argument that holds none.
std::vector<std::filesystem::path> kit_punch_dirs(const std::vector<std::string>& arguments);

}  // namespace rangefill::cli
