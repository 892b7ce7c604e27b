// rangefill holes MESH: every boundary loop with its size, perimeter, area and share of its
// component's area (what decides whether repair takes it for a border).
#include <cstdio>
#include <iostream>

#include "cli.h"
#include "rangefill/core/topology.h"
#include "rangefill/hole/holes.h"
#include "rangefill/reports/reports.h"

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
    nlohmann::json report = reports::holes_report(mesh, topology, holes, options.list_vertices);
    report["file"] = options.mesh;
    print_json(report);
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
