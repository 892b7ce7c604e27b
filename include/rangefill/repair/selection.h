// Each hole filled by what its own surface says works best: an outer band of known faces around
// the hole is hidden, the enlarged hole is filled by each candidate filler, each fill is scored
// by its distance to the hidden band (as the filler made it: the angle pass, which reshapes
// triangles over the same surface, is left out of the test), and the hole itself is then filled by
// the candidates in the order of their scores (self-validation; the band plays the part of the
// ground truth the hole lacks).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/hole/fill.h"
#include "rangefill/hole/holes.h"
#include "rangefill/repair/fill_chain.h"
#include "rangefill/repair/fillers.h"

namespace rangefill {

/// The default candidates (how they were chosen: DEVELOPERS.md).
inline constexpr const char* kDefaultCandidates = "fairing,fairing:c1,plane:telea";

struct SelectionOptions {
  FillerChain candidates = make_fillers(kDefaultCandidates);  // none: no selection
  int band_rings = 2;  // rings of known faces hidden around the hole
};

/// A hole enlarged by a hidden band of known faces, on a copy of the surface around it.
struct BandTest {
  Mesh mesh;                 // the faces around the hole but the band, vertices renumbered
  BoundaryLoop hole;         // the enlarged hole's loop in `mesh`
  std::vector<Vec3> hidden;  // the band's vertices that `mesh` does not keep: the ground truth
};

/// The band test of `hole` (a loop of `surface`): the faces within `band_rings` rings of its loop
/// hidden, the faces within `context_rings` more kept around them. nullopt when the band does not
/// make one larger hole of a disk's topology (it reaches another loop, pinches, or hides no
/// vertex). The enlarged loop's area_share is that of its area in the hole's component.
std::optional<BandTest> hide_band(const SurfaceContext& surface, const BoundaryLoop& hole,
                                  int band_rings, int context_rings);

/// The root mean square distance from the test's hidden points to the fill of its hole.
double band_distance(const BandTest& test, const Fill& fill);

/// Fills `hole` as fill_by_chain does, the chain preceded by the candidates in the order of their
/// band test's scores (candidates refused on the test come after, in their order). Without
/// candidates, or when hide_band gives no test, it is fill_by_chain. `report.selection` receives
/// each candidate's score.
std::optional<Fill> fill_by_selection(const SurfaceContext& surface, const BoundaryLoop& hole,
                                      const SelectionOptions& selection, const FillerChain& chain,
                                      const ChainOptions& options, HoleReport& report);

}  // namespace rangefill
