// "foe": MAP inpainting under a Fields-of-Experts prior (rangefill/foe.h).
#pragma once

#include "rangefill/inpaint/foe_map.h"
#include "rangefill/inpaint/foe_model.h"
#include "rangefill/inpaint/inpainter.h"

namespace rangefill {

/// MAP inpainting (foe_map) on the mask's bounding box grown by the filter
/// footprint (the only cliques that change), inputs divided by foe_input_divisor. Known pixels are
/// returned exactly. With a `start` back-end, inference starts from that back-end's fill of the
/// image (options.start_from_image is then implied) instead of the harmonic fill.
class FoeInpainter : public Inpainter {
 public:
  explicit FoeInpainter(FoeModel model, const FoeMapOptions& options = {},
                        std::unique_ptr<Inpainter> start = nullptr);
  std::string name() const override { return "foe"; }
  void inpaint(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out) const override;
  const FoeModel& model() const { return model_; }

 private:
  FoeModel model_;
  FoeMapOptions options_;
  std::unique_ptr<Inpainter> start_;
};

}  // namespace rangefill
