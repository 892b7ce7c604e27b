// "foe": MAP inpainting under a Fields-of-Experts prior (rangefill/foe.h).
#pragma once

#include "rangefill/inpaint/foe_map.h"
#include "rangefill/inpaint/foe_model.h"
#include "rangefill/inpaint/inpainter.h"

namespace rangefill {

/// How the "foe" back-end is made (inpainters.h).
struct FoeBackendOptions {
  std::string model = "depth";  // a shipped model's name or a model file
  /// What inference starts from, "harmonic" (its own Laplace fill) or another back-end's name
  /// (not foe): E is not convex, and the MAP found is the local minimum near the start.
  std::string start = "harmonic";
  double tolerance = 1e-6;  // stop when a step lowers E by less than this share of E
  int iterations = 100;     // or after this many steps
};

/// MAP inpainting (foe_map) on the mask's bounding box grown by the filter
/// footprint (the only cliques that change), inputs divided by foe_input_divisor. Known pixels are
/// returned exactly. With a `start` back-end, inference starts from that back-end's fill of the
/// image (options.start_from_image is then implied) instead of the harmonic fill. With
/// `clique_weights` (foe_clique_weights, the size of the images to inpaint; empty for none), each
/// clique's experts count by its weight.
class FoeInpainter : public Inpainter {
 public:
  explicit FoeInpainter(FoeModel model, const FoeMapOptions& options = {},
                        std::unique_ptr<Inpainter> start = nullptr, cv::Mat clique_weights = {});
  std::string name() const override { return "foe"; }
  void inpaint(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out) const override;
  /// Cliques weighted by foe_clique_weights(guide, model().size, sigma); inference starts from the
  /// harmonic fill guided alike (the start given otherwise reads no guide).
  std::unique_ptr<Inpainter> guided(const cv::Mat& guide, float sigma) const override;
  const FoeModel& model() const { return model_; }

 private:
  FoeModel model_;
  FoeMapOptions options_;
  std::unique_ptr<Inpainter> start_;
  cv::Mat clique_weights_;
};

}  // namespace rangefill
