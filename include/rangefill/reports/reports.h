// The JSON reports of `rangefill repair --json`, `depth --json` and `holes --json`, shared by the
// command and the Python module (python/), so that both describe a result in the same words.
#pragma once

#include <nlohmann/json.hpp>

#include "rangefill/core/topology.h"
#include "rangefill/depth/fill_depth.h"
#include "rangefill/hole/holes.h"
#include "rangefill/repair/pipeline.h"

namespace rangefill::reports {

/// What repair() did: the input's defects, every hole's report (its attempts and stage times),
/// the restoration matrix (eq. 17) and why each loop of the result is open.
nlohmann::json repair_report(const RepairResult& result);

/// What fill_depth() did, its filled_mask aside: holes, filled, pixels, and the holes left by
/// reason.
nlohmann::json depth_fill_report(const DepthFillStats& stats);

/// The boundary loops of `mesh` (find_holes), each with its size, perimeter, area, component,
/// area share and whether repair takes it for a border (and its vertex ids with `vertices`); d_m
/// and the topology's defects.
nlohmann::json holes_report(const Mesh& mesh, const MeshTopology& topology, const HoleSet& holes,
                            bool vertices);

}  // namespace rangefill::reports
