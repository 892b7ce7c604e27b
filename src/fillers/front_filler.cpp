#include "rangefill/fillers/front_filler.h"

namespace rangefill {

namespace {

class FrontFiller : public Filler {
 public:
  explicit FrontFiller(const FrontFillerOptions& options) : options_(options) {}
  std::string name() const override { return "front"; }
  std::string method() const override { return "front"; }

  FillOutcome fill(const HoleContext& context, const AcceptFill& accept,
                   FillerLog& /*log*/) const override {
    const SurfaceContext& surface = context.surface;
    std::vector<Vec3> samples, normals;
    for (int v : context.zone.vertices) {
      samples.push_back(surface.mesh.positions[v]);
      normals.push_back(vertex_normal(surface.mesh, surface.topology, v));
    }
    FillOutcome outcome = fill_by_front(
        surface.mesh, surface.topology, surface.faces, context.hole,
        MlsSurface(std::move(samples), std::move(normals), options_.mls), options_.front);
    if (Fill* fill = std::get_if<Fill>(&outcome)) return accept(std::move(*fill));
    return outcome;
  }

 private:
  FrontFillerOptions options_;
};

}  // namespace

std::shared_ptr<const Filler> make_front_filler(const FrontFillerOptions& options) {
  return std::make_shared<FrontFiller>(options);
}

}  // namespace rangefill
