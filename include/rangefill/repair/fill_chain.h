// The fill chain: the fillers of one hole (filler.h), tried in order until the acceptance step
// (acceptance.h) takes a fill (Pérez et al., Sections V–VIII; Tekumalla & Cohen's advancing
// front; Liepa's triangulation). The report keeps every refusal and the seconds of each step.
#pragma once

#include <optional>

#include "rangefill/hole/acceptance.h"
#include "rangefill/hole/filler.h"
#include "rangefill/hole/zone.h"
#include "rangefill/repair/hole_report.h"

namespace rangefill {

struct ChainOptions {
  ZoneOptions zone;  // the hole's zone of interest (Section V), grown once for every filler
  AcceptanceOptions acceptance;
  ImagesCallback on_images;  // HoleContext::on_images
  /// In the last pass, a fill of a part of the loop (Section VI-C), whose rest would stay open,
  /// gives way to a later filler that fills the whole loop.
  bool last_pass = false;
};

/// Fills `hole` by the first filler of `chain` whose fill the acceptance step takes; nullopt
/// when none does (and when the zone is empty: no filler is tried). A filler that throws
/// ProcessingError is refused (Refusal::error). Reads `surface` only; safe to call concurrently.
/// `report` receives the filler, the refusals, the steps' seconds and the figures of what was
/// made (its id, pass, loop, boundary_vertices and area are the caller's to set).
std::optional<Fill> fill_by_chain(const SurfaceContext& surface, const BoundaryLoop& hole,
                                  const FillerChain& chain, const ChainOptions& options,
                                  HoleReport& report);

}  // namespace rangefill
