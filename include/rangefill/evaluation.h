// Scoring a repair against ground truth: the faces punched out of a closed mesh.
#pragma once

#include <string>
#include <vector>

#include "rangefill/metrics.h"
#include "rangefill/pipeline.h"
#include "rangefill/punch.h"

namespace rangefill {

/// How well one punched hole was restored, distances in world units.
struct HoleScore {
  int hole = 0;         // index in PunchResult::holes
  double area = 0;      // area of the removed faces
  bool filled = false;  // closed: no boundary loop of the result runs along it
  std::string failure;
  SurfaceDistance distance;  // first = the patch, second = the removed faces
  double edge_ratio = 0;     // mean patch edge / d_m
  int new_vertices = 0;
  int new_faces = 0;
  double seconds = 0;
  std::string method;  // of the pass-0 fill (HoleReport::method)
  int zone_faces = 0;
  HoleReport::Stages stages;
};

/// Scores a repair of `punched.mesh` against the faces removed from `original`: each punched hole
/// is matched to the report of the loop it left, its patch to the generated faces with that
/// report's id. Distances are sampled at spacing d_m / 4. Holes the repair did not attempt count as
/// not filled.
std::vector<HoleScore> score_repair(const Mesh& original, const PunchResult& punched,
                                    const RepairResult& repaired, double mean_edge);

}  // namespace rangefill
