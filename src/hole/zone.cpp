#include "rangefill/hole/zone.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "rangefill/core/errors.h"

namespace rangefill {

int rings_for_hole(double hole_area, double mean_edge, const ZoneOptions& options) {
  if (!(mean_edge > 0)) throw InvalidInput("zone: mean edge length must be positive");
  const double area = hole_area / (mean_edge * mean_edge);  // eq. 2 in units of d_m
  const double rings = area / (0.106 * options.kappa * area + 18.0);
  return std::clamp(static_cast<int>(std::lround(rings)), options.min_rings, options.max_rings);
}

namespace {

// Angle between two normals. Eq. 4 writes arctan(|n×m| / |n·m|), which folds angles beyond 90°
// back below it and would accept a surface turning back on itself; our normals are oriented, so
// the signed dot product is used.
double angle_between(const Vec3& n, const Vec3& m) {
  return std::atan2(n.cross(m).norm(), n.dot(m));
}

Vec3 normalized_or_zero(const Vec3& v) {
  const double length = v.norm();
  return length > 0 ? Vec3(v / length) : Vec3::Zero();
}

std::vector<int> sorted_unique(std::vector<int> values) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

}  // namespace

namespace {

// Adds the faces whose three vertices all joined the zone (the keys of `diffused`).
void close_slivers(const Mesh& mesh, const MeshTopology& topology,
                   const std::unordered_map<int, Vec3>& diffused,
                   std::unordered_set<int>& zone_faces) {
  for (const auto& [v, normal] : diffused) {
    for_each_face_of_vertex(topology, v, [&](int face) {
      const Triangle& t = mesh.triangles[face];
      if (diffused.count(t[0]) && diffused.count(t[1]) && diffused.count(t[2])) {
        zone_faces.insert(face);
      }
    });
  }
}

// The ids of the loops other than `hole` with a vertex among the zone's (ascending).
std::vector<int> other_holes_reached(const HoleSet& holes, const BoundaryLoop& hole,
                                     const std::vector<int>& zone_vertices) {
  std::vector<int> reached;
  for (const BoundaryLoop& other : holes.loops) {
    if (other.id == hole.id) continue;
    if (std::any_of(other.vertices.begin(), other.vertices.end(), [&](int v) {
          return std::binary_search(zone_vertices.begin(), zone_vertices.end(), v);
        })) {
      reached.push_back(other.id);
    }
  }
  return reached;
}

}  // namespace

Zone grow_zone(const Mesh& mesh, const MeshTopology& topology, const HoleSet& holes,
               const BoundaryLoop& hole, double mean_edge, const ZoneOptions& options) {
  Zone zone;
  zone.rings = options.rings > 0 ? options.rings : rings_for_hole(hole.area, mean_edge, options);
  const double gamma = options.gamma_degrees * M_PI / 180.0;

  // Diffused normals N' of the zone's vertices (membership of this map = zone vertex).
  std::unordered_map<int, Vec3> diffused;
  std::unordered_set<int> zone_faces;
  std::vector<int> search = sorted_unique(hole.vertices);
  const auto normal = [&](int v) { return vertex_normal(mesh, topology, v); };
  for (int v : search) diffused.emplace(v, normalized_or_zero(normal(v)));

  for (int ring = 1; ring <= zone.rings && !search.empty(); ++ring) {
    const std::unordered_set<int> is_search(search.begin(), search.end());
    std::vector<int> candidates;
    for (int v : search) {
      for_each_face_of_vertex(topology, v, [&](int face) {
        if (!zone_faces.count(face)) candidates.push_back(face);
      });
    }
    std::vector<int> next_search;
    bool grew = false;
    for (int face : sorted_unique(std::move(candidates))) {
      Vec3 search_normal = Vec3::Zero();
      int new_vertices[3], new_count = 0;
      bool rejected = false;
      for (int v : mesh.triangles[face]) {
        if (is_search.count(v)) search_normal += diffused.at(v);
        if (!diffused.count(v)) new_vertices[new_count++] = v;
      }
      for (int k = 0; k < new_count && !rejected; ++k) {
        const Vec3 candidate = normal(new_vertices[k]);
        for (int v : mesh.triangles[face]) {
          if (is_search.count(v) && angle_between(candidate, diffused.at(v)) > gamma) {
            rejected = true;
          }
        }
      }
      if (rejected) {
        ++zone.rejected_faces;
        continue;
      }
      zone_faces.insert(face);
      grew = true;
      const Vec3 pull = options.alpha * ring * normalized_or_zero(search_normal);
      for (int k = 0; k < new_count; ++k) {
        const int v = new_vertices[k];
        diffused.emplace(v, normalized_or_zero((normal(v) + pull) / 2));  // eq. 5
        next_search.push_back(v);
      }
    }
    if (grew) zone.rings_grown = ring;
    search = sorted_unique(std::move(next_search));
  }

  close_slivers(mesh, topology, diffused, zone_faces);
  zone.faces.assign(zone_faces.begin(), zone_faces.end());
  std::sort(zone.faces.begin(), zone.faces.end());
  std::vector<int> vertices;
  for (int face : zone.faces) {
    for (int v : mesh.triangles[face]) vertices.push_back(v);
  }
  zone.vertices = sorted_unique(std::move(vertices));
  zone.other_holes = other_holes_reached(holes, hole, zone.vertices);
  return zone;
}

}  // namespace rangefill
