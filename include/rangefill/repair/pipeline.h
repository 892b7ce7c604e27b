// The repair pipeline (Pérez et al., Sections IV–IX): every hole becomes a range image, is restored
// by an inpainter, mapped back to 3D, stitched and merged; then holes are looked for again.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rangefill/core/intersection.h"
#include "rangefill/core/mesh.h"
#include "rangefill/inpaint/inpainter.h"
#include "rangefill/repair/back_projection.h"
#include "rangefill/repair/complex_hole.h"
#include "rangefill/repair/front.h"
#include "rangefill/repair/holes.h"
#include "rangefill/repair/projection.h"
#include "rangefill/repair/range_image.h"
#include "rangefill/repair/stitch.h"
#include "rangefill/repair/trend.h"
#include "rangefill/repair/zone.h"

namespace rangefill {

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
  } stages;
  std::vector<int> other_holes;  // other loops the zone reached
  bool filled = false;
  std::string method;   // "plane", "front", "plane, in part" (VI-C: the rest is a new hole),
                        // "Liepa" or "least area"
  std::string failure;  // why not, when not filled
};

/// Everything a person needs to look at one hole's images (see RepairOptions::on_images).
struct HoleImages {
  int id = 0;  // HoleReport::id
  const RangeImage& image;
  const cv::Mat& restored;
};

/// How holes are filled: through range images on projection planes (the Pérez pipeline), or by
/// the advancing front (Tekumalla & Cohen).
enum class Filler { plane, front };

struct RepairOptions {
  Filler filler = Filler::plane;
  bool fallback_front = true;       // holes the planes cannot fill go to the advancing front
  bool fallback_least_area = true;  // ... and then to a patch of the loop without new vertices
                                    // (Liepa's weight, else least area)
  FrontOptions front;
  MlsOptions mls;
  std::string inpainter = "foe";  // the depth-trained FoE: best on the benchmark (README)
  InpainterOptions inpainting;
  /// Trend removed before inpainting and added back (trend.h); the back-end then only restores the
  /// residual. OpenCV's telea and ns are weighted means at heart and, on curved surfaces, pull a
  /// fill towards the lower ring around the hole (a cap of a sphere came back below its cutting
  /// plane); a quadric continued from the rim overshoots a wide spherical cap (1 d_m on 40°).
  /// Automatic by default (the sphere where it fits the rim better, else the quadric): on the
  /// punched benchmark H median 0.44 against 0.46 d_m with the quadric alone (foe; README).
  /// `none` is the paper's pipeline, for ablations.
  TrendKind trend = TrendKind::automatic;
  double min_rim_support = 0.9;  // a plane whose image sees less of the hole's surroundings
                                 // (rim_support after gap filling) gives way to the next
  double trend_ring = 3;         // known pixels within this many pixels of the hole are fitted
  ZoneOptions zone;
  ProjectionOptions projection;
  RangeImageOptions image;
  BackProjectionOptions back_projection;
  std::vector<int> holes;  // ids of the input's loops to fill (each must exist: else
                           // InvalidInput); empty = every loop but the borders
  /// With `holes` empty, input loops for which is_border(loop, border_share) holds are left open
  /// as the border of an open surface (holes.h); 0 fills them too.
  double border_share = kBorderShare;
  int max_hole_edges = 0;    // loops with more boundary edges are left open; 0 = no limit
  double max_hole_area = 0;  // loops with a larger area are left open; 0 = no limit
  int passes = 8;   // rounds of detect–fill–merge (Section IX); complex holes take one per part
  int threads = 1;  // holes of a pass are independent; the result does not depend on it
  std::function<void(const HoleReport&)> on_hole;    // after each hole (any thread, serialised)
  std::function<void(const HoleImages&)> on_images;  // after each inpainting (serialised)
};

/// Why a boundary loop of the repaired mesh is open.
enum class OpenReason {
  border,           // an input loop taken for the border of an open surface (border_share)
  not_selected,     // an input loop that RepairOptions::holes does not list
  over_size_limit,  // an input loop over max_hole_edges or max_hole_area
  failed,           // a loop that was to be filled: no strategy could fill it, or what is left of
                    // a hole filled in part when the passes ran out
};

/// "border", "not selected", "over size limit", "failed".
std::string open_reason_name(OpenReason reason);

/// A boundary loop of the repaired mesh.
struct OpenLoop {
  int id = 0;    // in find_holes of the repaired mesh
  int hole = 0;  // the input loop's id when the loop is one, else the HoleReport::id of the hole
                 // whose fill left it
  int edges = 0;
  double area = 0;
  double area_share = 0;  // BoundaryLoop::area_share; for a loop the options left open, in the
                          // input (what they judged), else in the result
  OpenReason reason = OpenReason::failed;
};

struct RepairResult {
  Mesh mesh;
  MeshDefects defects;  // of the input
  std::vector<HoleReport> holes;
  /// Eq. 17: row 0 counts the input's vertices, edges and faces; row i + 1 those added by the i-th
  /// filled hole, in the order the fills were merged.
  std::vector<std::array<long long, 3>> restoration_matrix;
  std::vector<OpenLoop> open_loops;  // every boundary loop of `mesh`, by id

  /// Open loops for `reason`.
  int open_count(OpenReason reason) const;
};

/// What every hole of a pass reads: the mesh and what is derived from it once per pass.
struct SurfaceContext {
  /// `mean_edge`: the d_m to use; 0 takes this mesh's.
  SurfaceContext(const Mesh& mesh, double mean_edge);
  const Mesh& mesh;
  MeshTopology topology;
  HoleSet holes;
  std::vector<Vec3> normals;  // area-weighted, from the faces
  double mean_edge;           // d_m
  IntersectionIndex faces;    // for refusing fills that would cut through the surface
};

/// Fills one hole. With Filler::plane: Sections V–VIII on the best acceptable plane, else the next
/// ones; then, if allowed, the advancing front; then a part of the hole (VI-C, complex_hole.h) with
/// a zone and planes of its own, the rest left to the next pass; then, if allowed, a patch of the
/// loop without new vertices (Liepa's weight, triangulate_loop_liepa, else least area). Reads
/// `surface` only; safe to call concurrently. `report` receives the figures of the stages it
/// reached (its id, pass, loop, boundary_vertices and area are the caller's to set). Throws
/// ProcessingError with the reasons when no filler succeeds (a fill is refused when it would not be
/// manifold or would intersect the surface or itself).
Fill fill_hole(const SurfaceContext& surface, const BoundaryLoop& hole, const Inpainter& inpainter,
               const RepairOptions& options, HoleReport& report);

/// Colours for new points (the advancing front's, say) from the colours of the hole's boundary
/// vertices, weighted by their inverse squared distance (Shepard). Requires mesh.has_colors().
std::vector<Rgb> boundary_colors(const Mesh& mesh, const std::vector<int>& boundary,
                                 const std::vector<Vec3>& points);

/// Appends a fill to the mesh with provenance `hole_id` (Section IX, eq. 16) and returns its row
/// of the restoration matrix (vertices, edges, faces added). When the mesh has colours, the new
/// vertices take fill.colors (restored with the geometry, Wang & Oliveira 4.4) or, when the fill
/// has none, boundary_colors.
std::array<long long, 3> merge_fill(Mesh& mesh, const Fill& fill, int hole_id);

/// Repairs every selected hole, in passes: all holes of a pass are filled against the same mesh
/// (in parallel when options.threads > 1) and merged in hole order, so the result is the same at
/// any thread count; then holes are detected again and the next pass fills those that are new.
/// Original vertices and faces keep their indices and values. A hole that fails is reported and
/// left open; so is, without a try, a loop through one of the input's unfillable_vertices
/// (topology.h), so that no generated face touches a non-manifold element. d_m is the input's mean
/// edge length throughout. `open_loops` says why each loop of the result is open.
RepairResult repair(const Mesh& mesh, const RepairOptions& options = {});

}  // namespace rangefill
