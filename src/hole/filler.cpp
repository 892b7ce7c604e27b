#include "rangefill/hole/filler.h"

#include <array>

namespace rangefill {

namespace {

// Where the fills of `holes` are to be tested against the surface: the box of each loop grown by
// its diameter on every side (a fill that reaches farther is tested against every face).
std::vector<std::array<Vec3, 2>> fill_regions(const Mesh& mesh, const HoleSet& holes) {
  std::vector<std::array<Vec3, 2>> regions;
  for (const BoundaryLoop& loop : holes.loops) {
    Vec3 low = mesh.positions[loop.vertices[0]], high = low;
    for (int v : loop.vertices) {
      low = low.cwiseMin(mesh.positions[v]);
      high = high.cwiseMax(mesh.positions[v]);
    }
    const Vec3 margin = Vec3::Constant((high - low).norm());
    regions.push_back({low - margin, high + margin});
  }
  return regions;
}

}  // namespace

SurfaceContext::SurfaceContext(const Mesh& surface_mesh, double mean_edge_length)
    : mesh(surface_mesh),
      topology(build_topology(surface_mesh)),
      holes(find_holes(surface_mesh, topology)),
      mean_edge(mean_edge_length > 0 ? mean_edge_length
                                     : rangefill::mean_edge_length(surface_mesh, topology)),
      faces(surface_mesh, fill_regions(surface_mesh, holes)) {}

void add_seconds(std::vector<StepSeconds>& steps, const std::string& step, double seconds) {
  for (StepSeconds& each : steps) {
    if (each.step == step) {
      each.seconds += seconds;
      return;
    }
  }
  steps.push_back({step, seconds});
}

double seconds_of(const std::vector<StepSeconds>& steps, const std::string& step) {
  for (const StepSeconds& each : steps) {
    if (each.step == step) return each.seconds;
  }
  return 0;
}

}  // namespace rangefill
