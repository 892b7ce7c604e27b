// rangefill info MESH: counts, components, boundary loops, defects, self-intersections, whether it
// is watertight, d_m, bounds.
#include <iomanip>
#include <iostream>
#include <numeric>

#include "cli.h"
#include "rangefill/core/intersection.h"
#include "rangefill/core/topology.h"
#include "rangefill/hole/holes.h"

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
  const MeshDefects defects = find_defects(mesh, topology);
  const double d_m = mean_edge_length(mesh, topology);
  const auto [lo, hi] = bounding_box(mesh);
  int unreferenced = 0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (topology.vertex_halfedge[v] == kNoFaces) ++unreferenced;
  }
  std::vector<int> all_faces(mesh.face_count());
  std::iota(all_faces.begin(), all_faces.end(), 0);
  const int self_intersections = count_self_intersections(mesh, all_faces);
  // A closed, consistently oriented 2-manifold that does not cut itself.
  const bool watertight = mesh.face_count() > 0 && holes.loops.empty() &&
                          holes.open_boundary_edges == 0 && defects.nonmanifold_edges == 0 &&
                          defects.misoriented_edges == 0 && defects.nonmanifold_vertices == 0 &&
                          self_intersections == 0;
  std::vector<int> loop_sizes;
  for (const BoundaryLoop& loop : holes.loops) loop_sizes.push_back(loop.vertices.size());

  if (options.json) {
    print_json({{"file", options.mesh},
                {"vertices", mesh.vertex_count()},
                {"faces", mesh.face_count()},
                {"components", holes.component_areas.size()},
                {"boundary_loops", loop_sizes},
                {"open_boundary_edges", holes.open_boundary_edges},
                {"nonmanifold_edges", defects.nonmanifold_edges},
                {"misoriented_edges", defects.misoriented_edges},
                {"nonmanifold_vertices", defects.nonmanifold_vertices},
                {"duplicated_faces", defects.duplicated_faces},
                {"degenerate_faces", defects.degenerate_faces},
                {"unreferenced_vertices", unreferenced},
                {"self_intersecting_face_pairs", self_intersections},
                {"watertight", watertight},
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
            << "faces                " << mesh.face_count() << "\n"
            << "attributes           " << (mesh.has_colors() ? "colour " : "")
            << (mesh.has_normals() ? "normal " : "")
            << (mesh.has_colors() || mesh.has_normals() ? "" : "none") << "\n"
            << "components           " << holes.component_areas.size() << "\n"
            << "boundary loops       " << holes.loops.size();
  if (!loop_sizes.empty()) {
    std::cout << " (edges:";
    for (int size : loop_sizes) std::cout << " " << size;
    std::cout << ")";
  }
  std::cout << "\n"
            << "non-manifold         " << defects.nonmanifold_edges << " edges, "
            << defects.nonmanifold_vertices << " vertices; " << defects.misoriented_edges
            << " misoriented edges\n"
            << "duplicated faces     " << defects.duplicated_faces << "\n"
            << "degenerate faces     " << defects.degenerate_faces << "\n"
            << "self-intersections   " << self_intersections << " face pairs\n"
            << "watertight           " << (watertight ? "yes" : "no") << "\n"
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
      "info",
      "Summarise a mesh: counts, components, boundary loops, defects, self-intersections, "
      "watertight or not, d_m");
  command->add_option("mesh", options->mesh, "Mesh file (.ply, .obj, .off, .stl)")->required();
  command->add_flag("--json", options->json, "Print a JSON object instead of text");
  command->callback([options, &runner] { runner = [options] { return run_info(*options); }; });
}

}  // namespace rangefill::cli
