#include "rangefill/repair/fill.h"

namespace rangefill {

std::string refusal_text(Refusal refusal) {
  switch (refusal) {
    case Refusal::nonmanifold_rim:
      return "touches a non-manifold edge or vertex";
    case Refusal::empty_zone:
      return "the zone of interest is empty";
    case Refusal::no_plane:
      return "no plane sees its rim from the front with a simple boundary (Section VI-C)";
    case Refusal::partial_view:
      return "the plane sees too little of the hole's surroundings";
    case Refusal::not_manifold:
      return "the fill would not join the mesh as a manifold";
    case Refusal::intersects:
      return "the fill would intersect the surface or itself";
    case Refusal::front_stuck:
      return "the advancing front did not close";
    case Refusal::no_part:
      return "no part of the complex hole could be filled";
    case Refusal::no_triangulation:
      return "no triangulation of its loop";
    case Refusal::error:
      return "a stage failed";
  }
  return "";
}

}  // namespace rangefill
