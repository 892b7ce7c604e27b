#include "rangefill/repair/fill_chain.h"

#include <chrono>

#include "rangefill/core/errors.h"

namespace rangefill {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// One filler on the hole, its time, its acceptance's and its own steps' in the report; a
// ProcessingError is its refusal.
FillOutcome run_filler(const Filler& filler, const HoleContext& context,
                       const ChainOptions& options, HoleReport& report) {
  double checking = 0;
  const AcceptFill accept = [&](Fill fill) {
    const Clock::time_point start = Clock::now();
    FillOutcome outcome = accept_fill(context.surface, std::move(fill), options.acceptance);
    checking += seconds_since(start);
    return outcome;
  };
  FillerLog log;
  const Clock::time_point start = Clock::now();
  FillOutcome outcome = [&]() -> FillOutcome {
    try {
      return filler.fill(context, accept, log);
    } catch (const ProcessingError& error) {
      return Refused{Refusal::error, error.what()};
    }
  }();
  add_seconds(report.steps, filler.name(), seconds_since(start) - checking);
  add_seconds(report.steps, "checking", checking);
  for (const StepSeconds& step : log.steps) add_seconds(report.steps, step.step, step.seconds);
  if (log.made_image) {
    report.image = log.image;
    report.zone_faces = log.image.visible_faces;
  }
  return outcome;
}

// The fill when there is one; else the refusal is recorded for `filler`.
std::optional<Fill> accepted(FillOutcome outcome, const Filler& filler, HoleReport& report) {
  if (Fill* fill = std::get_if<Fill>(&outcome)) return std::move(*fill);
  report.attempts.push_back(
      {filler.name(), filler.method(), std::get<Refused>(std::move(outcome))});
  return std::nullopt;
}

// "hole 3: plane: the plane sees only 80% of the hole's surroundings; front: ...".
std::string failure_text(int id, const std::vector<Attempt>& attempts) {
  std::string text = "hole " + std::to_string(id) + ": ";
  for (size_t i = 0; i < attempts.size(); ++i) {
    const Attempt& attempt = attempts[i];
    if (i > 0) text += "; ";
    if (!attempt.method.empty()) text += attempt.method + ": ";
    text += attempt.refused.detail.empty() ? refusal_text(attempt.refused.refusal)
                                           : attempt.refused.detail;
  }
  return text;
}

}  // namespace

std::optional<Fill> fill_by_chain(const SurfaceContext& surface, const BoundaryLoop& hole,
                                  const FillerChain& chain, const ChainOptions& options,
                                  HoleReport& report) {
  const Clock::time_point start = Clock::now();
  const Zone zone = grow_zone(surface.mesh, surface.topology, surface.holes, hole,
                              surface.mean_edge, options.zone);
  add_seconds(report.steps, "zone", seconds_since(start));
  report.rings = zone.rings;
  report.zone_faces = static_cast<int>(zone.faces.size());
  report.other_holes = zone.other_holes;
  const HoleContext context{surface, hole, zone, options.zone, report.id, options.on_images};

  std::optional<Fill> fill;
  const Filler* filled_by = nullptr;
  if (zone.faces.empty()) report.attempts.push_back({"", "", {Refusal::empty_zone, ""}});
  for (size_t i = 0; i < chain.size() && !fill && !zone.faces.empty(); ++i) {
    fill = accepted(run_filler(*chain[i], context, options, report), *chain[i], report);
    if (!fill) continue;
    filled_by = chain[i].get();
    // The rest of a part would stay open after the last pass: a later filler that fills the
    // whole loop comes first.
    for (size_t j = i + 1; j < chain.size() && options.last_pass && fill->boundary != hole.vertices;
         ++j) {
      if (auto whole =
              accepted(run_filler(*chain[j], context, options, report), *chain[j], report)) {
        fill = std::move(whole);
        filled_by = chain[j].get();
        break;
      }
    }
  }
  report.seconds = seconds_since(start);
  if (!fill) {
    report.failure = failure_text(hole.id, report.attempts);
    return std::nullopt;
  }
  report.filler = filled_by->name();
  report.method = filled_by->method();
  report.new_vertices = static_cast<int>(fill->points.size());
  report.new_faces = static_cast<int>(fill->triangles.size());
  report.filled = true;
  return fill;
}

}  // namespace rangefill
