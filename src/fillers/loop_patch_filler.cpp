#include "rangefill/fillers/loop_patch_filler.h"

#include <set>

#include "rangefill/core/errors.h"
#include "rangefill/fillers/loop_patch.h"

namespace rangefill {

namespace {

std::vector<Vec3> loop_positions(const Mesh& mesh, const BoundaryLoop& hole) {
  std::vector<Vec3> positions;
  for (int v : hole.vertices) positions.push_back(mesh.positions[v]);
  return positions;
}

// A patch of the hole's own loop, as `triangles` of its corners, through `accept`.
FillOutcome loop_patch(const BoundaryLoop& hole, std::vector<Triangle> triangles,
                       const AcceptFill& accept) {
  if (triangles.empty()) return Refused{Refusal::no_triangulation, ""};
  Fill fill;
  fill.boundary = hole.vertices;
  fill.triangles = std::move(triangles);
  return accept(std::move(fill));
}

class LiepaFiller : public Filler {
 public:
  std::string name() const override { return "liepa"; }
  std::string method() const override { return "Liepa"; }

  FillOutcome fill(const HoleContext& context, const AcceptFill& accept,
                   FillerLog& /*log*/) const override {
    const Mesh& mesh = context.surface.mesh;
    const MeshTopology& topology = context.surface.topology;
    const BoundaryLoop& hole = context.hole;
    const int n = static_cast<int>(hole.vertices.size());
    std::vector<Vec3> third_points;
    for (int k = 0; k < n; ++k) {
      const int a = hole.vertices[k], b = hole.vertices[(k + 1) % n];
      const int along = find_halfedge(mesh, topology, a, b);
      if (along < 0) {
        throw ProcessingError("hole " + std::to_string(hole.id) + ": not a border loop");
      }
      // The corner of the face outside opposite the edge: where its previous half-edge starts.
      const int third = mesh.triangles[halfedge_face(along)][prev_halfedge(along) % 3];
      third_points.push_back(mesh.positions[third]);
    }
    return loop_patch(hole, triangulate_loop_liepa(loop_positions(mesh, hole), third_points),
                      accept);
  }
};

class LeastAreaFiller : public Filler {
 public:
  std::string name() const override { return "least-area"; }
  std::string method() const override { return "least area"; }

  FillOutcome fill(const HoleContext& context, const AcceptFill& accept,
                   FillerLog& /*log*/) const override {
    const Mesh& mesh = context.surface.mesh;
    const MeshTopology& topology = context.surface.topology;
    const BoundaryLoop& hole = context.hole;
    std::set<std::pair<int, int>> forbidden;
    for (size_t i = 0; i < hole.vertices.size(); ++i) {
      for (size_t j = i + 2; j < hole.vertices.size(); ++j) {
        const int a = hole.vertices[i], b = hole.vertices[j];
        if (has_edge(mesh, topology, a, b)) {
          forbidden.emplace(static_cast<int>(i), static_cast<int>(j));
        }
      }
    }
    return loop_patch(hole, triangulate_loop_least_area(loop_positions(mesh, hole), forbidden),
                      accept);
  }
};

}  // namespace

std::shared_ptr<const Filler> make_liepa_filler() {
  return std::make_shared<LiepaFiller>();
}

std::shared_ptr<const Filler> make_least_area_filler() {
  return std::make_shared<LeastAreaFiller>();
}

}  // namespace rangefill
