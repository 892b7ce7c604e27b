#include "rangefill/hole/acceptance.h"

#include <numeric>

#include "rangefill/hole/patch_angles.h"

namespace rangefill {

namespace {

// A fill triangle meets a face of the surface or a non-adjacent fill triangle.
bool fill_intersects(const SurfaceContext& surface, const Fill& fill) {
  const int boundary_size = static_cast<int>(fill.boundary.size());
  Mesh own;  // the fill alone, its boundary first
  for (int v : fill.boundary) own.positions.push_back(surface.mesh.positions[v]);
  own.positions.insert(own.positions.end(), fill.points.begin(), fill.points.end());
  own.triangles = fill.triangles;
  for (const Triangle& t : fill.triangles) {
    Triangle corners;
    for (int k = 0; k < 3; ++k) corners[k] = t[k] < boundary_size ? fill.boundary[t[k]] : -1;
    if (!surface.faces
             .intersecting_faces(own.positions[t[0]], own.positions[t[1]], own.positions[t[2]],
                                 corners)
             .empty()) {
      return true;
    }
  }
  std::vector<int> all(own.triangles.size());
  std::iota(all.begin(), all.end(), 0);
  return count_self_intersections(own, all) > 0;
}

}  // namespace

FillOutcome accept_fill(const SurfaceContext& surface, Fill fill,
                        const AcceptanceOptions& options) {
  if (options.larger_angles) {
    fill = with_larger_angles(surface.mesh, surface.topology, std::move(fill));
  }
  if (const auto defect = fill_defect(surface.mesh, surface.topology, fill)) {
    return Refused{Refusal::not_manifold, *defect};
  }
  if (fill_intersects(surface, fill)) return Refused{Refusal::intersects, ""};
  return fill;
}

}  // namespace rangefill
