// One interface for the ways of filling a hole, as inpainter.h is for the back-ends: a filler has
// a name and its own options (given when it is made, fillers.h), reads a hole's context and gives
// a fill or a refusal (fill.h). Whether a fill is accepted is the pipeline's step, not the
// filler's (acceptance.h): a filler hands every fill it makes to the `accept` it is given.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "rangefill/core/intersection.h"
#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"
#include "rangefill/hole/fill.h"
#include "rangefill/hole/holes.h"
#include "rangefill/hole/zone.h"

namespace rangefill {

/// What every hole of a pass reads: the mesh and what is derived from it once per pass.
struct SurfaceContext {
  /// `mean_edge`: the d_m to use; 0 takes this mesh's.
  SurfaceContext(const Mesh& mesh, double mean_edge);
  const Mesh& mesh;
  MeshTopology topology;
  HoleSet holes;
  double mean_edge;         // d_m
  IntersectionIndex faces;  // for refusing fills that would cut the surface (near the loops)
};

struct HoleImages;  // plane_filler.h
/// Called with each range image a filler inpaints, for a person to look at.
using ImagesCallback = std::function<void(const HoleImages&)>;

/// What a filler reads of one hole.
struct HoleContext {
  const SurfaceContext& surface;
  const BoundaryLoop& hole;
  const Zone& zone;                 // its zone of interest (Section V), never empty
  const ZoneOptions& zone_options;  // how it was grown (for the zones of a part of it)
  int id = 0;                       // the hole's id in the repair (HoleReport::id)
  ImagesCallback on_images;         // may be empty (band tests, selection.h, show nothing)
};

/// Seconds spent in one named step, summed over its runs.
struct StepSeconds {
  std::string step;
  double seconds = 0;
};

/// Adds `seconds` to `step` in `steps`, appending the step when it is new.
void add_seconds(std::vector<StepSeconds>& steps, const std::string& step, double seconds);

/// The seconds of `step` in `steps` (0 when it did not run).
double seconds_of(const std::vector<StepSeconds>& steps, const std::string& step);

/// What the range image of a hole showed (Section VI-B), when a filler made one.
struct ImageFigures {
  int visible_faces = 0;  // faces of the zone seen from the plane
  int width = 0, height = 0;
  int masked_pixels = 0;
  int gap_pixels = 0;
  double rim_support = 0;      // range_image.h
  std::string trend = "none";  // the trend fitted (after fallbacks)
};

/// What a filler tells of its work on one hole besides the fill.
struct FillerLog {
  std::vector<StepSeconds> steps;  // its own steps
  bool made_image = false;
  ImageFigures image;  // the last range image made, when made_image
};

/// The pipeline's acceptance step as a filler sees it: a fill in; the fill as it joins the mesh,
/// or why it cannot, out.
using AcceptFill = std::function<FillOutcome(Fill)>;

class Filler {
 public:
  virtual ~Filler() = default;
  /// The name it was made by (fillers.h): "fairing", "fairing:c1", "plane:telea", ...
  virtual std::string name() const = 0;
  /// What reports call its fills: "fairing", "plane", "plane, in part", "front", "Liepa",
  /// "least area".
  virtual std::string method() const = 0;
  /// Rings of faces around the loop it reads beyond the hole's zone (0: none).
  virtual int context_rings() const { return 0; }
  /// A fill of context.hole that `accept` took, or the refusal: of the filler, or of `accept`.
  /// Every fill made goes through `accept`; a filler with several tries (planes, continuity
  /// orders, parts) hands each to it in turn. Reads the context only; safe to call concurrently.
  virtual FillOutcome fill(const HoleContext& context, const AcceptFill& accept,
                           FillerLog& log) const = 0;
};

/// Fillers in the order they are tried.
using FillerChain = std::vector<std::shared_ptr<const Filler>>;

}  // namespace rangefill
