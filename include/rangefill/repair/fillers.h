// The fillers by name, as make_inpainter makes the back-ends: each made once for a repair with
// its own part of FillerOptions (filler_options.h), then shared by every hole (filler.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rangefill/hole/filler.h"

namespace rangefill {

struct FillerOptions;  // filler_options.h

/// "fairing" (the faired patch, fairing_filler.h; "fairing:c0", ":c1", ":c2" of that continuity),
/// "plane" (the paper's image pipeline, plane_filler.h; "plane:BACKEND" with a back-end of its
/// own), "plane-in-part" (Section VI-C), "front" (front_filler.h), "liepa" and "least-area"
/// (loop_patch_filler.h). Throws InvalidInput on another name, listing the known ones.
std::shared_ptr<const Filler> make_filler(const std::string& name, const FillerOptions& options);
/// The same with every filler's default options.
std::shared_ptr<const Filler> make_filler(const std::string& name);

/// The base names make_filler accepts, in a stable order (the variants after a colon aside).
std::vector<std::string> filler_names();

/// The default chain: the faired patch, then range images on planes, the advancing front and the
/// loop's patches.
inline constexpr const char* kDefaultFiller = "fairing";
inline constexpr const char* kDefaultFallbacks = "plane,front,least-area";

/// The chain of `filler` and its `fallbacks`, tried in the order listed: a comma-separated list
/// of filler names, where "least-area" stands for "liepa,least-area" (Liepa's weight, else least
/// area), or "none". A filler already in the chain is not added twice. With a plane filler in the
/// chain, plane-in-part (with that filler's back-end) comes before the loop patches, else last.
/// Throws InvalidInput on an unknown name.
FillerChain make_filler_chain(const std::string& filler, const std::string& fallbacks,
                              const FillerOptions& options);
FillerChain make_filler_chain(const std::string& filler, const std::string& fallbacks);

/// The fillers of a comma-separated list of names, none for "none" or "" (the candidates of a band
/// test, selection.h). Throws InvalidInput on an unknown name or a repeated one.
FillerChain make_fillers(const std::string& list, const FillerOptions& options);
FillerChain make_fillers(const std::string& list);

/// The names of `chain`'s fillers, in order.
std::vector<std::string> filler_chain_names(const FillerChain& chain);

}  // namespace rangefill
