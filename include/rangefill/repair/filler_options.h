// Every filler's options, each filler reading its own part (fillers.h makes them).
#pragma once

#include "rangefill/repair/fairing_filler.h"
#include "rangefill/repair/front_filler.h"
#include "rangefill/repair/plane_filler.h"

namespace rangefill {

struct FillerOptions {
  FairingOptions fairing;    // fairing, fairing:cK
  PlaneFillerOptions plane;  // plane, plane:BACKEND, plane-in-part
  FrontFillerOptions front;  // front
};

}  // namespace rangefill
