#include "rangefill/reports/reports.h"

namespace rangefill::reports {

namespace {

// Why the last attempt on hole `id` failed ("" when none did).
std::string failure_of(const RepairResult& result, int id) {
  for (auto hole = result.holes.rbegin(); hole != result.holes.rend(); ++hole) {
    if (hole->id == id && !hole->filled) return hole->failure;
  }
  return "";
}

nlohmann::json hole_json(const HoleReport& hole) {
  nlohmann::json attempts = nlohmann::json::array();
  for (const Attempt& attempt : hole.attempts) {
    attempts.push_back({{"strategy", attempt.method},
                        {"filler", attempt.filler},
                        {"refusal", refusal_name(attempt.refused.refusal)},
                        {"detail", attempt.refused.detail}});
  }
  nlohmann::json selection = nlohmann::json::array();
  for (const CandidateScore& score : hole.selection) {
    selection.push_back({{"candidate", score.candidate},
                         {"band_rms", score.score ? nlohmann::json(*score.score) : nullptr},
                         {"seconds", score.seconds}});
  }
  nlohmann::json steps = nlohmann::json::object();
  for (const StepSeconds& step : hole.steps) steps[step.step] = step.seconds;
  return {{"id", hole.id},
          {"pass", hole.pass},
          {"loop", hole.loop},
          {"boundary_vertices", hole.boundary_vertices},
          {"area", hole.area},
          {"rings", hole.rings},
          {"zone_faces", hole.zone_faces},
          {"image_size", {hole.image.width, hole.image.height}},
          {"masked_pixels", hole.image.masked_pixels},
          {"gap_pixels", hole.image.gap_pixels},
          {"trend", hole.image.trend},
          {"new_vertices", hole.new_vertices},
          {"new_faces", hole.new_faces},
          {"seconds", hole.seconds},
          {"stage_seconds", steps},
          {"method", hole.method},
          {"filler", hole.filler},
          {"selection", selection},
          {"selected", hole.selected},
          {"other_holes", hole.other_holes},
          {"filled", hole.filled},
          {"rim_support", hole.image.rim_support},
          {"attempts", attempts},
          {"failure", hole.failure}};
}

}  // namespace

nlohmann::json repair_report(const RepairResult& result) {
  nlohmann::json holes = nlohmann::json::array();
  for (const HoleReport& hole : result.holes) holes.push_back(hole_json(hole));
  nlohmann::json open_loops = nlohmann::json::array();
  for (const OpenLoop& loop : result.open_loops) {
    nlohmann::json entry = {{"id", loop.id},
                            {"hole", loop.hole},
                            {"edges", loop.edges},
                            {"area", loop.area},
                            {"area_share", loop.area_share},
                            {"reason", open_reason_name(loop.reason)}};
    if (loop.reason == OpenReason::failed) entry["failure"] = failure_of(result, loop.hole);
    open_loops.push_back(entry);
  }
  const MeshDefects& defects = result.defects;
  return {{"defects",
           {{"nonmanifold_edges", defects.nonmanifold_edges},
            {"misoriented_edges", defects.misoriented_edges},
            {"nonmanifold_vertices", defects.nonmanifold_vertices},
            {"duplicated_faces", defects.duplicated_faces},
            {"degenerate_faces", defects.degenerate_faces}}},
          {"holes", holes},
          {"restoration_matrix", result.restoration_matrix},
          {"loops_left_open", result.open_loops.size()},
          {"open_loops", open_loops}};
}

nlohmann::json depth_fill_report(const DepthFillStats& stats) {
  auto left = [](const DepthFillStats::Left& left) {
    return nlohmann::json{{"holes", left.holes}, {"pixels", left.pixels}};
  };
  return {{"holes", stats.holes},
          {"filled", stats.filled},
          {"filled_pixels", stats.filled_pixels},
          {"at_edge", stats.at_edge},
          {"left_holes", stats.left_holes()},
          {"left_pixels", stats.left_pixels()},
          {"left",
           {{"too_large", left(stats.too_large)},
            {"at_border", left(stats.at_border)},
            {"without_support", left(stats.without_support)}}}};
}

nlohmann::json holes_report(const Mesh& mesh, const MeshTopology& topology, const HoleSet& holes,
                            bool vertices) {
  nlohmann::json loops = nlohmann::json::array();
  for (const BoundaryLoop& loop : holes.loops) {
    nlohmann::json entry = {{"id", loop.id},
                            {"edges", loop.vertices.size()},
                            {"perimeter", loop.perimeter},
                            {"area", loop.area},
                            {"component", loop.component},
                            {"area_share", loop.area_share},
                            {"border", is_border(loop)}};
    if (vertices) entry["vertices"] = loop.vertices;
    loops.push_back(entry);
  }
  return {{"mean_edge_length", mean_edge_length(mesh, topology)},
          {"loops", loops},
          {"pinched_vertices", holes.pinched_vertices},
          {"open_boundary_edges", holes.open_boundary_edges},
          {"nonmanifold_edges", topology.nonmanifold_edge_count},
          {"misoriented_edges", topology.misoriented_edge_count},
          {"nonmanifold_vertices", topology.nonmanifold_vertices}};
}

}  // namespace rangefill::reports
