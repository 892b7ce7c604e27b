// Every filler's options, each filler reading its own part (fillers.h makes them).
#pragma once

#include "rangefill/fillers/fairing_filler.h"
#include "rangefill/fillers/front_filler.h"
#include "rangefill/image/plane_filler.h"

namespace rangefill {

struct FillerOptions {
  FairingOptions fairing;    // fairing, fairing:cK
  PlaneFillerOptions plane;  // plane, plane:BACKEND, plane-in-part
  FrontFillerOptions front;  // front
};

}  // namespace rangefill
