#include "kit_punch.h"

#include <algorithm>
#include <map>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "rangefill/core/errors.h"
#include "rangefill/io/mesh_io.h"

namespace rangefill::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using Position = std::array<double, 3>;

Position key(const Vec3& p) {
  return {p.x() + 0.0, p.y() + 0.0, p.z() + 0.0};  // -0 as +0, as the kit matches them
}

json read_holes_json(const fs::path& file) {
  if (!fs::is_regular_file(file)) throw InvalidInput(file.string() + ": no such file");
  json document = json::parse(read_file(file), nullptr, false);
  if (document.is_discarded() || !document.is_object() || !document.contains("holes") ||
      !document.contains("d_m")) {
    throw InvalidInput(file.string() + ": not a holes.json of the mesh kit's punch");
  }
  return document;
}

// Appends the faces of `truth` (read from `file`) to `original`: a corner at a position of
// `vertex_at` takes that vertex; other corners are the hole's removed vertices, appended once.
// Returns the appended faces.
std::vector<int> append_truth(const Mesh& truth, const fs::path& file,
                              std::map<Position, int>& vertex_at, int holed_vertices,
                              Mesh& original) {
  std::vector<int> index(truth.vertex_count());
  for (int v = 0; v < truth.vertex_count(); ++v) {
    const auto [at, added] = vertex_at.emplace(key(truth.positions[v]), original.vertex_count());
    if (added) {
      add_vertex(original, truth.positions[v], kOriginal);
    } else if (at->second >= holed_vertices) {
      throw InvalidInput(file.string() + ": vertex " + std::to_string(v) +
                         " is a removed vertex of another hole");
    }
    index[v] = at->second;
  }
  std::vector<int> faces;
  for (const Triangle& t : truth.triangles) {
    faces.push_back(add_face(original, {index[t[0]], index[t[1]], index[t[2]]}, kOriginal));
  }
  return faces;
}

}  // namespace

KitPunch read_kit_punch(const fs::path& dir) {
  const fs::path holes_file = dir / "holes.json";
  const json document = read_holes_json(holes_file);
  KitPunch kit;
  kit.mean_edge = document.at("d_m").get<double>();
  const Mesh holed = load_mesh((dir / document.value("holed_mesh", "holed.ply")).string());
  kit.original = make_mesh(holed.positions, holed.triangles);
  std::map<Position, int> vertex_at;
  for (int v = 0; v < holed.vertex_count(); ++v) vertex_at.emplace(key(holed.positions[v]), v);

  std::vector<PunchedHole> holes;
  try {
    for (const json& entry : document.at("holes")) {
      const int id = entry.at("id").get<int>();
      const fs::path file = dir / ("gt_hole_" + std::to_string(id) + ".ply");
      PunchedHole hole;
      hole.shape = entry.value("elongated", false) ? HoleShape::elongated : HoleShape::disk;
      hole.radius = entry.at("radius").get<double>();
      hole.bending = entry.at("curvature").get<double>();
      hole.curvature = curvature_from_name(entry.at("curvature_class").get<std::string>());
      hole.sharp_feature = entry.value("on_feature", false);
      hole.removed_faces = append_truth(load_mesh(file.string()), file, vertex_at,
                                        holed.vertex_count(), kit.original);
      if (hole.removed_faces.empty()) throw InvalidInput(file.string() + ": no face");
      hole.centre = kit.original.triangles[hole.removed_faces.front()][0];
      holes.push_back(std::move(hole));
    }
  } catch (const json::exception& error) {
    throw InvalidInput(holes_file.string() + ": " + error.what());
  }
  kit.punched = remove_holes(kit.original, std::move(holes));
  if (kit.punched.mesh.positions != holed.positions ||
      kit.punched.mesh.triangles != holed.triangles) {
    throw InvalidInput(dir.string() +
                       ": holed.ply is not the closed mesh of its holes' faces without them "
                       "(unreferenced vertices?)");
  }
  kit.punched.mesh = holed;
  return kit;
}

std::vector<fs::path> kit_punch_dirs(const std::vector<std::string>& arguments) {
  std::vector<fs::path> dirs;
  for (const std::string& argument : arguments) {
    const size_t before = dirs.size();
    if (fs::is_regular_file(fs::path(argument) / "holes.json")) {
      dirs.emplace_back(argument);
    } else if (fs::is_directory(argument)) {
      for (const fs::directory_entry& entry : fs::recursive_directory_iterator(argument)) {
        if (entry.path().filename() == "holes.json") dirs.push_back(entry.path().parent_path());
      }
    }
    if (dirs.size() == before) throw UsageError(argument + ": no holes.json at or under it");
    std::sort(dirs.begin() + static_cast<long>(before), dirs.end());
  }
  return dirs;
}

}  // namespace rangefill::cli
