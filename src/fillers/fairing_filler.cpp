#include "rangefill/fillers/fairing_filler.h"

#include <optional>

namespace rangefill {

namespace {

class FairingFiller : public Filler {
 public:
  FairingFiller(std::string name, const FairingOptions& options)
      : name_(std::move(name)), options_(options) {}
  std::string name() const override { return name_; }
  std::string method() const override { return "fairing"; }
  int context_rings() const override { return options_.rings; }

  FillOutcome fill(const HoleContext& context, const AcceptFill& accept,
                   FillerLog& /*log*/) const override {
    const SurfaceContext& surface = context.surface;
    // A cap over a fifth of its component (asked for with --fill-all) is no hole to fair: its
    // patch would be as large as the surface, and as slow.
    const double area_in_dm2 = context.hole.area / (surface.mean_edge * surface.mean_edge);
    if (is_border(context.hole) || area_in_dm2 > kMaxFairedArea) {
      return Refused{Refusal::border_sized, ""};
    }
    std::optional<Refused> first;
    for (FairingOptions options = options_; options.continuity >= 0; --options.continuity) {
      FillOutcome outcome =
          fill_by_fairing(surface.mesh, surface.topology, context.hole, surface.mean_edge, options);
      if (Fill* fill = std::get_if<Fill>(&outcome)) outcome = accept(std::move(*fill));
      if (std::holds_alternative<Fill>(outcome)) return outcome;
      if (!first) first = std::get<Refused>(std::move(outcome));
    }
    return *first;
  }

 private:
  std::string name_;
  FairingOptions options_;
};

}  // namespace

std::shared_ptr<const Filler> make_fairing_filler(const std::string& name,
                                                  const FairingOptions& options) {
  return std::make_shared<FairingFiller>(name, options);
}

}  // namespace rangefill
