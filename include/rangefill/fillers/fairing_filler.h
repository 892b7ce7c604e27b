// The faired patch (fairing.h) as a filler.
#pragma once

#include <memory>
#include <string>

#include "rangefill/fillers/fairing.h"
#include "rangefill/hole/filler.h"

namespace rangefill {

/// Holes larger than this many d_m² are refused (border_sized): the fairing's linear systems
/// grow faster than the image pipeline's (some 3500 new vertices at this size).
inline constexpr double kMaxFairedArea = 3000;

/// The faired patch of options.continuity, else of a lower one: a higher order continues the
/// surroundings' curvature further and may overshoot into the surface where a thin part turns (a
/// horn, an ear); the first refusal is the one kept. Refuses (border_sized) a loop is_border
/// takes for a border and one over kMaxFairedArea d_m². `name`: "fairing", or "fairing:c0",
/// ":c1", ":c2" (options.continuity given by the name).
std::shared_ptr<const Filler> make_fairing_filler(const std::string& name,
                                                  const FairingOptions& options);

}  // namespace rangefill
