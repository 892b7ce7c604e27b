// The advancing front over an MLS surface of the hole's zone (Tekumalla & Cohen) as a filler.
#pragma once

#include <memory>

#include "rangefill/fillers/front.h"
#include "rangefill/fillers/mls.h"
#include "rangefill/hole/filler.h"

namespace rangefill {

struct FrontFillerOptions {
  FrontOptions front;
  MlsOptions mls;  // the surface the front's points are projected onto
};

/// fill_by_front over the MLS surface of the zone's vertices and their normals. Named "front".
std::shared_ptr<const Filler> make_front_filler(const FrontFillerOptions& options);

}  // namespace rangefill
