// Patches of a hole's loop without new vertices (loop_patch.h) as fillers: the last resort.
#pragma once

#include <memory>

#include "rangefill/hole/filler.h"

namespace rangefill {

/// What MeshLab's Close Holes does: Liepa's weight, whose dihedral angles against the faces
/// outside keep the patch from folding into the surface. Named "liepa".
std::shared_ptr<const Filler> make_liepa_filler();

/// The least-area patch of the loop, avoiding the chords the mesh already has. Named
/// "least-area".
std::shared_ptr<const Filler> make_least_area_filler();

}  // namespace rangefill
