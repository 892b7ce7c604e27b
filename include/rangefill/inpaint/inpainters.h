// The back-ends by name, as make_filler makes the fillers (repair/fillers.h): each made with its
// own part of InpainterOptions.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "rangefill/inpaint/foe.h"
#include "rangefill/inpaint/inpainter.h"
#include "rangefill/inpaint/mls_height.h"
#include "rangefill/inpaint/opencv_inpaint.h"

namespace rangefill {

/// Every back-end's options, each back-end reading its own part.
struct InpainterOptions {
  OpenCvInpaintOptions opencv;  // telea, ns
  MlsHeightOptions mls;         // mls
  FoeBackendOptions foe;        // foe
};

/// The back-ends by name ("telea", "ns", ...), or by "foe:MODEL" to choose the FoE model (a shipped
/// model's name or a model file; overrides options.foe.model). Throws InvalidInput for an unknown
/// name, listing the known ones.
std::unique_ptr<Inpainter> make_inpainter(std::string_view spec,
                                          const InpainterOptions& options = {});

/// The names make_inpainter accepts, in a stable order.
std::vector<std::string> inpainter_names();

}  // namespace rangefill
