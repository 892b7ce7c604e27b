#include "rangefill/repair/fillers.h"

#include <algorithm>

#include "rangefill/core/errors.h"
#include "rangefill/fillers/loop_patch_filler.h"
#include "rangefill/repair/filler_options.h"

namespace rangefill {

namespace {

std::vector<std::string> split_names(const std::string& list) {
  std::vector<std::string> names;
  if (list.empty() || list == "none") return names;
  for (size_t start = 0; start <= list.size();) {
    const size_t end = std::min(list.find(',', start), list.size());
    names.push_back(list.substr(start, end - start));
    start = end + 1;
  }
  return names;
}

[[noreturn]] void unknown_filler(const std::string& name) {
  std::string known;
  for (const std::string& base : filler_names()) known += (known.empty() ? "" : ", ") + base;
  throw InvalidInput("unknown filler '" + name + "' (expected " + known +
                     "; fairing:c0|c1|c2, plane:BACKEND)");
}

// The back-end a plane filler's name gives ("plane:telea": telea), else the options'.
PlaneFillerOptions plane_options(const std::string& variant, const FillerOptions& options) {
  PlaneFillerOptions plane = options.plane;
  if (!variant.empty()) plane.inpainter = variant;
  return plane;
}

}  // namespace

std::vector<std::string> filler_names() {
  return {"fairing", "plane", "plane-in-part", "front", "liepa", "least-area"};
}

std::shared_ptr<const Filler> make_filler(const std::string& name, const FillerOptions& options) {
  const size_t colon = name.find(':');
  const std::string base = name.substr(0, colon);
  const std::string variant = colon == std::string::npos ? "" : name.substr(colon + 1);
  if (base == "fairing") {
    FairingOptions fairing = options.fairing;
    if (variant == "c0" || variant == "c1" || variant == "c2") {
      fairing.continuity = variant[1] - '0';
    } else if (!variant.empty()) {
      unknown_filler(name);
    }
    return make_fairing_filler(name, fairing);
  }
  if (base == "plane" && (colon == std::string::npos || !variant.empty())) {
    return make_plane_filler(name, plane_options(variant, options));
  }
  if (!variant.empty() || colon != std::string::npos) unknown_filler(name);
  if (name == "plane-in-part") return make_plane_in_part_filler(options.plane);
  if (name == "front") return make_front_filler(options.front);
  if (name == "liepa") return make_liepa_filler();
  if (name == "least-area") return make_least_area_filler();
  unknown_filler(name);
}

FillerChain make_filler_chain(const std::string& filler, const std::string& fallbacks,
                              const FillerOptions& options) {
  std::vector<std::string> names = {filler};
  const auto add = [&](const std::string& name) {
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  };
  for (const std::string& name : split_names(fallbacks)) {
    if (name == "least-area") {
      if (std::find(names.begin(), names.end(), "liepa") == names.end()) {
        add("liepa");
        add("least-area");
      }
    } else {
      add(name);
    }
  }
  FillerChain chain;
  for (const std::string& name : names) chain.push_back(make_filler(name, options));
  const auto plane = std::find_if(chain.begin(), chain.end(),
                                  [](const auto& each) { return each->method() == "plane"; });
  if (plane != chain.end() &&
      std::find(names.begin(), names.end(), "plane-in-part") == names.end()) {
    const std::string variant = (*plane)->name().substr(std::string("plane").size());
    const auto liepa = std::find_if(chain.begin(), chain.end(),
                                    [](const auto& each) { return each->name() == "liepa"; });
    chain.insert(liepa, make_plane_in_part_filler(
                            plane_options(variant.empty() ? "" : variant.substr(1), options)));
  }
  return chain;
}

FillerChain make_fillers(const std::string& list, const FillerOptions& options) {
  FillerChain fillers;
  for (const std::string& name : split_names(list)) {
    for (const auto& other : fillers) {
      if (other->name() == name) throw InvalidInput("candidate '" + name + "' listed twice");
    }
    fillers.push_back(make_filler(name, options));
  }
  return fillers;
}

std::shared_ptr<const Filler> make_filler(const std::string& name) {
  return make_filler(name, FillerOptions());
}

FillerChain make_filler_chain(const std::string& filler, const std::string& fallbacks) {
  return make_filler_chain(filler, fallbacks, FillerOptions());
}

FillerChain make_fillers(const std::string& list) {
  return make_fillers(list, FillerOptions());
}

std::vector<std::string> filler_chain_names(const FillerChain& chain) {
  std::vector<std::string> names;
  for (const auto& filler : chain) names.push_back(filler->name());
  return names;
}

}  // namespace rangefill
