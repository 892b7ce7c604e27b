// The repair pipeline (Pérez et al., Sections IV–IX): the loops to fill are chosen, each is filled
// by its band test's winner or the fill chain (selection.h, fill_chain.h) against the same mesh,
// every fill passes the acceptance step (acceptance.h), the fills are merged (Section IX), and
// holes are looked for again, pass after pass.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/core/parallel.h"
#include "rangefill/core/topology.h"
#include "rangefill/hole/fill.h"
#include "rangefill/hole/filler.h"
#include "rangefill/hole/holes.h"
#include "rangefill/hole/zone.h"
#include "rangefill/repair/fillers.h"
#include "rangefill/repair/hole_report.h"
#include "rangefill/repair/selection.h"

namespace rangefill {

/// How holes are chosen and filled: the fillers (each made with its own options, fillers.h), which
/// loops, in how many passes.
/// ReadOptions::spare_share (io/mesh_io.h) for a mesh read to be repaired: room for its fills, so
/// that `repair(std::move(mesh))` appends them without moving the mesh's arrays.
inline constexpr double kFillShare = 1.0 / 64;

struct RepairOptions {
  FillerChain chain = make_filler_chain(kDefaultFiller, kDefaultFallbacks);  // tried in order
  ZoneOptions zone;        // each hole's zone of interest (Section V), what its fillers read
  std::vector<int> holes;  // ids of the input's loops to fill (each must exist: else
                           // InvalidInput); empty = every loop but the borders
  /// With `holes` empty, input loops for which is_border(loop, border_share) holds are left open
  /// as the border of an open surface (holes.h); 0 fills them too.
  double border_share = kBorderShare;
  int max_hole_edges = 0;      // loops with more boundary edges are left open; 0 = no limit
  double max_hole_area = 0;    // loops with a larger area are left open; 0 = no limit
  SelectionOptions selection;  // each hole's filler chosen by a band test (selection.h), tried
                               // before `chain`; no candidates: the chain alone
  int passes = 8;  // rounds of detect–fill–merge (Section IX); complex holes take one per part
  int threads = hardware_threads();  // holes of a pass filled at once; the result does not
                                     // depend on it
  std::function<void(const HoleReport&)> on_hole;  // after each hole (any thread, serialised)
  ImagesCallback on_images;  // after each inpainting (plane_filler.h; serialised too)
};

/// Why a boundary loop of the repaired mesh is open.
enum class OpenReason {
  border,           // an input loop taken for the border of an open surface (border_share)
  not_selected,     // an input loop that RepairOptions::holes does not list
  over_size_limit,  // an input loop over max_hole_edges or max_hole_area
  failed,           // a loop that was to be filled: no filler could fill it, or what is left of
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
RepairResult repair(const Mesh& input, const RepairOptions& options = {});
/// The same, repairing `input` itself rather than a copy: one mesh in memory, not two.
RepairResult repair(Mesh&& input, const RepairOptions& options = {});

}  // namespace rangefill
