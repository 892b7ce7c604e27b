// rangefill info MESH: counts, components, boundary loops, non-manifold elements, d_m, bounds.
#include <iomanip>
#include <iostream>

#include "cli.h"
#include "rangefill/holes.h"
#include "rangefill/topology.h"

namespace rangefill::cli {

namespace {

struct InfoOptions {
  std::string mesh;
  bool json = false;
};

int run_info(const InfoOptions& options) {
  const Mesh mesh = load_mesh(options.mesh);
  const MeshTopology topology = build_topology(mesh);
  const HoleSet holes = find_holes(mesh, topology);
  const double d_m = mean_edge_length(mesh, topology);
  const auto [lo, hi] = bounding_box(mesh);
  int unreferenced = 0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (topology.faces_of_vertex_begin(v) == topology.faces_of_vertex_end(v)) ++unreferenced;
  }
  int zero_area = 0;
  for (int f = 0; f < mesh.face_count(); ++f) {
    if (triangle_cross(mesh, f).squaredNorm() == 0) ++zero_area;
  }
  std::vector<int> loop_sizes;
  for (const BoundaryLoop& loop : holes.loops) loop_sizes.push_back(loop.vertices.size());

  if (options.json) {
    print_json({{"file", options.mesh},
                {"vertices", mesh.vertex_count()},
                {"faces", mesh.face_count()},
                {"components", topology.component_count},
                {"boundary_loops", loop_sizes},
                {"nonmanifold_edges", topology.nonmanifold_edge_count},
                {"misoriented_edges", topology.misoriented_edge_count},
                {"nonmanifold_vertices", topology.nonmanifold_vertices.size()},
                {"unreferenced_vertices", unreferenced},
                {"zero_area_faces", zero_area},
                {"has_colors", mesh.has_colors()},
                {"has_normals", mesh.has_normals()},
                {"mean_edge_length", d_m},
                {"bounding_box", {{lo.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), hi.z()}}},
                {"diagonal", (hi - lo).norm()}});
    return kOk;
  }
  std::cout << std::setprecision(6);
  std::cout << "file                 " << options.mesh << "\n"
            << "vertices             " << mesh.vertex_count()
            << (unreferenced ? " (" + std::to_string(unreferenced) + " unreferenced)" : "") << "\n"
            << "faces                " << mesh.face_count()
            << (zero_area ? " (" + std::to_string(zero_area) + " of zero area)" : "") << "\n"
            << "attributes           " << (mesh.has_colors() ? "colour " : "")
            << (mesh.has_normals() ? "normal " : "")
            << (mesh.has_colors() || mesh.has_normals() ? "" : "none") << "\n"
            << "components           " << topology.component_count << "\n"
            << "boundary loops       " << holes.loops.size();
  if (!loop_sizes.empty()) {
    std::cout << " (edges:";
    for (int size : loop_sizes) std::cout << " " << size;
    std::cout << ")";
  }
  std::cout << "\n"
            << "non-manifold         " << topology.nonmanifold_edge_count << " edges, "
            << topology.nonmanifold_vertices.size() << " vertices; "
            << topology.misoriented_edge_count << " misoriented edges\n"
            << "mean edge length d_m " << d_m << "\n"
            << "bounding box         [" << lo.x() << ", " << lo.y() << ", " << lo.z() << "] .. ["
            << hi.x() << ", " << hi.y() << ", " << hi.z() << "], diagonal " << (hi - lo).norm()
            << "\n";
  return kOk;
}

}  // namespace

void add_info_command(CLI::App& app, Runner& runner) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* command = app.add_subcommand(
      "info", "Summarise a mesh: counts, components, boundary loops, non-manifold elements, d_m");
  command->add_option("mesh", options->mesh, "Mesh file (.ply, .obj, .off, .stl)")->required();
  command->add_flag("--json", options->json, "Print a JSON object instead of text");
  command->callback([options, &runner] { runner = [options] { return run_info(*options); }; });
}

}  // namespace rangefill::cli
