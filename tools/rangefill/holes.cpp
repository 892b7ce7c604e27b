// rangefill holes MESH: every boundary loop with its size, perimeter, area and share of its
// component's area (what decides whether repair takes it for a border).
#include <cstdio>
#include <iostream>

#include "cli.h"
#include "rangefill/core/topology.h"
#include "rangefill/repair/holes.h"

namespace rangefill::cli {

namespace {

struct HolesOptions {
  std::string mesh;
  bool json = false;
  bool list_vertices = false;
};

int run_holes(const HolesOptions& options) {
  const Mesh mesh = load_mesh(options.mesh);
  const MeshTopology topology = build_topology(mesh);
  const HoleSet holes = find_holes(mesh, topology);

  if (options.json) {
    nlohmann::json loops = nlohmann::json::array();
    for (const BoundaryLoop& loop : holes.loops) {
      nlohmann::json entry = {{"id", loop.id},
                              {"edges", loop.vertices.size()},
                              {"perimeter", loop.perimeter},
                              {"area", loop.area},
                              {"component", loop.component},
                              {"area_share", loop.area_share},
                              {"border", is_border(loop)}};
      if (options.list_vertices) entry["vertices"] = loop.vertices;
      loops.push_back(entry);
    }
    print_json({{"file", options.mesh},
                {"mean_edge_length", mean_edge_length(mesh, topology)},
                {"loops", loops},
                {"pinched_vertices", holes.pinched_vertices},
                {"open_boundary_edges", holes.open_boundary_edges},
                {"nonmanifold_edges", topology.nonmanifold_edge_count},
                {"misoriented_edges", topology.misoriented_edge_count},
                {"nonmanifold_vertices", topology.nonmanifold_vertices}});
    return kOk;
  }
  std::printf("%s: %zu boundary loops\n", options.mesh.c_str(), holes.loops.size());
  if (!holes.loops.empty()) {
    std::printf("%5s %7s %13s %13s %9s %6s  %s\n", "hole", "edges", "perimeter", "area",
                "component", "share", "note");
  }
  for (const BoundaryLoop& loop : holes.loops) {
    std::printf("%5d %7zu %13.6g %13.6g %9d %5.1f%%  %s\n", loop.id, loop.vertices.size(),
                loop.perimeter, loop.area, loop.component, 100 * loop.area_share,
                is_border(loop) ? "border of an open surface (repair leaves it open)" : "");
    if (options.list_vertices) {
      std::printf("      vertices:");
      for (int v : loop.vertices) std::printf(" %d", v);
      std::printf("\n");
    }
  }
  if (topology.nonmanifold_edge_count || topology.misoriented_edge_count ||
      !topology.nonmanifold_vertices.empty() || holes.open_boundary_edges) {
    std::printf(
        "non-manifold: %d edges, %zu vertices; %d misoriented edges; %d boundary edges on "
        "no closed loop\n",
        topology.nonmanifold_edge_count, topology.nonmanifold_vertices.size(),
        topology.misoriented_edge_count, holes.open_boundary_edges);
  }
  return kOk;
}

}  // namespace

void add_holes_command(CLI::App& app, Runner& runner) {
  auto options = std::make_shared<HolesOptions>();
  CLI::App* command =
      app.add_subcommand("holes", "List the boundary loops (holes) of a mesh (Pérez et al., IV)");
  command->add_option("mesh", options->mesh, "Mesh file (.ply, .obj, .off, .stl)")->required();
  command->add_flag("--json", options->json, "Print a JSON object instead of a table");
  command->add_flag("--vertices", options->list_vertices, "Also list each loop's vertex ids");
  command->callback([options, &runner] { runner = [options] { return run_holes(*options); }; });
}

}  // namespace rangefill::cli
