#include "rangefill/evaluation.h"

#include "rangefill/holes.h"

namespace rangefill {

std::vector<HoleScore> score_repair(const Mesh& original, const PunchResult& punched,
                                    const RepairResult& repaired, double mean_edge) {
  // Punched hole of each input vertex on a removed face (holes are apart, so at most one).
  std::vector<int> hole_of_vertex(original.vertex_count(), -1);
  for (size_t h = 0; h < punched.holes.size(); ++h) {
    for (int face : punched.holes[h].removed_faces) {
      for (int v : original.triangles[face]) hole_of_vertex[v] = static_cast<int>(h);
    }
  }
  const HoleSet loops = find_holes(punched.mesh, build_topology(punched.mesh));
  std::vector<HoleScore> scores(punched.holes.size());
  for (size_t h = 0; h < scores.size(); ++h) {
    scores[h].hole = static_cast<int>(h);
    scores[h].failure = "not attempted";
    for (int face : punched.holes[h].removed_faces)
      scores[h].area += 0.5 * triangle_cross(original, face).norm();
  }
  for (const HoleReport& report : repaired.holes) {
    if (report.pass != 0) continue;
    const int first = loops.loops.at(report.loop).vertices.front();
    const int h = hole_of_vertex[punched.original_vertex[first]];
    if (h < 0) continue;
    HoleScore& score = scores[h];
    score.filled = report.filled;  // until a loop of it is found open below
    score.failure = report.failure;
    score.new_vertices = report.new_vertices;
    score.new_faces = report.new_faces;
    score.seconds = report.seconds;
    score.method = report.method;
    score.zone_faces = report.zone_faces;
    score.stages = report.stages;
    if (!report.filled) continue;
    const std::vector<int> patch = faces_of_hole(repaired.mesh, report.id);
    score.distance = surface_distance(repaired.mesh, patch, original,
                                      punched.holes[h].removed_faces, mean_edge / 4);
    score.edge_ratio = mean_edge_length(repaired.mesh, patch) / mean_edge;
  }
  // A hole partly filled (Section VI-C) whose rest stayed open is not filled.
  for (const BoundaryLoop& loop : find_holes(repaired.mesh, build_topology(repaired.mesh)).loops) {
    for (int v : loop.vertices) {
      if (v >= punched.mesh.vertex_count()) continue;
      const int h = hole_of_vertex[punched.original_vertex[v]];
      if (h < 0 || !scores[h].filled) continue;
      scores[h].filled = false;
      scores[h].failure =
          "partly filled; a loop of " + std::to_string(loop.vertices.size()) + " edges stays open";
    }
  }
  return scores;
}

}  // namespace rangefill
