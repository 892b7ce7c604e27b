// The fill chain: the strategies that fill one hole, tried in the order of FillOptions::strategies
// until one gives a fill that joins the mesh as a manifold without cutting it (Pérez et al.,
// Sections V–VIII; Tekumalla & Cohen's advancing front; Liepa's triangulation). Each strategy
// returns a fill or a refusal (fill.h); the report keeps every refusal.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rangefill/core/intersection.h"
#include "rangefill/core/mesh.h"
#include "rangefill/core/topology.h"
#include "rangefill/inpaint/inpainter.h"
#include "rangefill/repair/back_projection.h"
#include "rangefill/repair/fairing.h"
#include "rangefill/repair/fill.h"
#include "rangefill/repair/front.h"
#include "rangefill/repair/holes.h"
#include "rangefill/repair/mls.h"
#include "rangefill/repair/projection.h"
#include "rangefill/repair/range_image.h"
#include "rangefill/repair/trend.h"
#include "rangefill/repair/zone.h"

namespace rangefill {

/// A way to fill a hole.
enum class Strategy {
  plane,          // Sections VI–VIII on the best acceptable projection plane, else the next ones
  front,          // the advancing front over an MLS surface of the zone (Tekumalla & Cohen)
  plane_in_part,  // VI-C: a part of a complex hole on planes of its own; the rest is a new hole
  liepa,          // a patch of the loop without new vertices: Liepa's weight (dihedral, area)
  least_area,     // a patch of the loop without new vertices of least area, avoiding mesh chords
  fairing,        // Liepa's patch refined, remeshed to d_m and faired (fairing.h)
};

/// "plane", "front", "plane, in part", "Liepa", "least area", "fairing".
std::string strategy_name(Strategy strategy);

/// What fills a hole first: range images on projection planes (the Pérez pipeline), the advancing
/// front, or the faired patch.
enum class Filler { plane, front, fairing };

/// "plane", "front", "fairing"; filler_from_name throws InvalidInput on another name.
std::string filler_name(Filler filler);
Filler filler_from_name(const std::string& name);

/// The default chain: the faired patch (C2, remeshed to d_m), which beat CGAL's fairing on the
/// mesh kit (README); then range images on planes, the advancing front and the loop's patches.
inline constexpr Filler kDefaultFiller = Filler::fairing;
inline constexpr const char* kDefaultFallbacks = "plane,front,least-area";

/// The chain of a filler and its fallbacks, tried in the order listed: a comma-separated list of
/// "fairing" (the faired patch), "plane" (range images), "front" (the advancing front) and
/// "least-area" (a patch of the loop: Liepa's weight, else least area), or "none". With planes in
/// the chain, the parts of a complex hole (VI-C) come before the loop patches, else last. A
/// strategy already in the chain (the filler among the fallbacks) is not tried twice. Throws
/// InvalidInput on an unknown fallback.
std::vector<Strategy> strategy_chain(Filler filler, const std::string& fallbacks);

/// One refusal met on the way: of a strategy, or (strategy empty) of the hole before any.
struct Attempt {
  std::optional<Strategy> strategy;
  Refused refused;
};

/// One candidate filler's band test (selection.h).
struct CandidateScore {
  std::string candidate;
  std::optional<double> score;  // RMS distance to the hidden band over d_m; none when refused
  double seconds = 0;
};

/// What happened to one hole.
struct HoleReport {
  int id = 0;    // unique over the run; the provenance of what it generated. In pass 0 it is the
                 // loop's id in the input (as `rangefill holes` lists them)
  int pass = 0;  // 0 for the input's holes, 1+ for holes found again after merging
  int loop = 0;  // id of the loop in its pass's HoleSet
  int boundary_vertices = 0;
  double area = 0;
  int rings = 0;  // ν
  int zone_faces = 0;
  cv::Size image_size;
  int masked_pixels = 0;
  int gap_pixels = 0;
  double rim_support = 0;             // of the image used (range_image.h)
  TrendKind trend = TrendKind::none;  // the trend actually fitted (after fallbacks)
  int new_vertices = 0;
  int new_faces = 0;
  double seconds = 0;             // whole hole
  struct Stages {                 // of which (seconds; summed over the planes tried)
    double zone = 0, planes = 0;  // grow_zone, find_projections
    double image = 0;             // visible_part, rasterize_zone, fill_small_gaps
    double inpainting = 0;        // the trend and the back-end (on the colours too, if any)
    double stitching = 0;         // back_project, triangulate_grid, stitch
    double checking = 0;          // the intersection test of the fill
    double front = 0;             // the advancing front, its checks included
    double fairing = 0;           // the faired patch, its checks included
  } stages;
  std::vector<int> other_holes;  // other loops the zone reached
  bool filled = false;
  std::optional<Strategy> strategy;       // what filled it
  std::string method;                     // who filled it, for tables: the strategy's name, or a
                                          // baseline's (baselines.h)
  std::vector<CandidateScore> selection;  // the band tests, when candidates were scored
  std::string selected;                   // the candidate that filled it, if one did
  std::vector<Attempt> attempts;          // every refusal, in the order met
  std::string failure;                    // when not filled: the refusals in one line
};

/// Everything a person needs to look at one hole's images (see FillOptions::on_images).
struct HoleImages {
  int id = 0;  // HoleReport::id
  const RangeImage& image;
  const cv::Mat& restored;
};

/// How one hole is filled.
struct FillOptions {
  std::vector<Strategy> strategies = strategy_chain(kDefaultFiller, kDefaultFallbacks);
  FrontOptions front;
  FairingOptions fairing;
  MlsOptions mls;
  std::string inpainter = "foe";  // the depth-trained FoE: best on the benchmark (README)
  InpainterOptions inpainting;
  /// Trend removed before inpainting and added back (trend.h); the back-end then only restores the
  /// residual. OpenCV's telea and ns are weighted means at heart and, on curved surfaces, pull a
  /// fill towards the lower ring around the hole (a cap of a sphere came back below its cutting
  /// plane); a quadric continued from the rim overshoots a wide spherical cap. Automatic by
  /// default (the sphere where it fits the rim better, else the quadric; README). `none` is the
  /// paper's pipeline, for ablations.
  TrendKind trend = TrendKind::automatic;
  double min_rim_support = 0.9;  // a plane whose image sees less of the hole's surroundings
                                 // (rim_support after gap filling) gives way to the next
  double trend_ring = 3;         // known pixels within this many pixels of the hole are fitted
  ZoneOptions zone;
  ProjectionOptions projection;
  RangeImageOptions image;
  BackProjectionOptions back_projection;
  std::function<void(const HoleImages&)> on_images;  // after each inpainting
};

/// What every hole of a pass reads: the mesh and what is derived from it once per pass.
struct SurfaceContext {
  /// `mean_edge`: the d_m to use; 0 takes this mesh's.
  SurfaceContext(const Mesh& mesh, double mean_edge);
  const Mesh& mesh;
  MeshTopology topology;
  HoleSet holes;
  double mean_edge;  // d_m
  IntersectionIndex
      faces;  // for refusing fills that would cut through the surface (near the loops)
  bool larger_angles = true;  // each fill given larger angles (patch_angles.h) before its checks
};

/// Fills `hole` by the first strategy of options.strategies that gives a fill; nullopt when none
/// does. A fill is refused when it would not join the mesh as a manifold or would intersect the
/// surface or itself; a stage that throws ProcessingError refuses its strategy (Refusal::error).
/// In the `last_pass`, a part of a complex hole (plane_in_part), whose rest would stay open, gives
/// way to a later strategy that fills the whole loop. Reads `surface` only; safe to call
/// concurrently. `report` receives the strategy, the refusals and the figures of the stages
/// reached (its id, pass, loop, boundary_vertices and area are the caller's to set).
std::optional<Fill> fill_by_chain(const SurfaceContext& surface, const BoundaryLoop& hole,
                                  const Inpainter& inpainter, const FillOptions& options,
                                  bool last_pass, HoleReport& report);

}  // namespace rangefill
