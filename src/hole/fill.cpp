#include "rangefill/hole/fill.h"

#include <map>

#include <Eigen/Geometry>

#include "rangefill/core/intersection.h"

namespace rangefill {

std::string refusal_text(Refusal refusal) {
  switch (refusal) {
    case Refusal::nonmanifold_rim:
      return "touches a non-manifold edge or vertex";
    case Refusal::empty_zone:
      return "the zone of interest is empty";
    case Refusal::no_plane:
      return "no plane sees its rim from the front with a simple boundary (Section VI-C)";
    case Refusal::partial_view:
      return "the plane sees too little of the hole's surroundings";
    case Refusal::not_manifold:
      return "the fill would not join the mesh as a manifold";
    case Refusal::intersects:
      return "the fill would intersect the surface or itself";
    case Refusal::front_stuck:
      return "the advancing front did not close";
    case Refusal::no_part:
      return "no part of the complex hole could be filled";
    case Refusal::no_triangulation:
      return "no triangulation of its loop";
    case Refusal::border_sized:
      return "the loop is too large for the faired patch (a border, or over 3000 d_m²)";
    case Refusal::error:
      return "a stage failed";
  }
  return "";
}

std::string refusal_name(Refusal refusal) {
  switch (refusal) {
    case Refusal::nonmanifold_rim:
      return "nonmanifold_rim";
    case Refusal::empty_zone:
      return "empty_zone";
    case Refusal::no_plane:
      return "no_plane";
    case Refusal::partial_view:
      return "partial_view";
    case Refusal::not_manifold:
      return "not_manifold";
    case Refusal::intersects:
      return "intersects";
    case Refusal::front_stuck:
      return "front_stuck";
    case Refusal::no_part:
      return "no_part";
    case Refusal::no_triangulation:
      return "no_triangulation";
    case Refusal::border_sized:
      return "border_sized";
    case Refusal::error:
      return "error";
  }
  return "";
}

namespace {

// A fill's triangles as corner positions and corner ids (mesh ids on the boundary, -1 for new
// points), with their bounding boxes.
struct PlacedTriangles {
  std::vector<std::array<Vec3, 3>> corners;
  std::vector<Triangle> ids;
  std::vector<Eigen::AlignedBox3d> boxes;
  Eigen::AlignedBox3d all;
};

PlacedTriangles placed(const Mesh& mesh, const Fill& fill) {
  const int boundary_size = static_cast<int>(fill.boundary.size());
  PlacedTriangles result;
  for (const Triangle& t : fill.triangles) {
    std::array<Vec3, 3> corners;
    Triangle ids;
    Eigen::AlignedBox3d box;
    for (int k = 0; k < 3; ++k) {
      const bool on_boundary = t[k] < boundary_size;
      ids[k] = on_boundary ? fill.boundary[t[k]] : -1;
      corners[k] = on_boundary ? mesh.positions[ids[k]] : fill.points[t[k] - boundary_size];
      box.extend(corners[k]);
    }
    result.corners.push_back(corners);
    result.ids.push_back(ids);
    result.boxes.push_back(box);
    result.all.extend(box);
  }
  return result;
}

}  // namespace

bool fills_intersect(const Mesh& mesh, const Fill& a, const Fill& b) {
  const PlacedTriangles first = placed(mesh, a), second = placed(mesh, b);
  if (!first.all.intersects(second.all)) return false;
  for (size_t i = 0; i < first.corners.size(); ++i) {
    if (!first.boxes[i].intersects(second.all)) continue;
    for (size_t j = 0; j < second.corners.size(); ++j) {
      if (first.boxes[i].intersects(second.boxes[j]) &&
          triangles_intersect(first.corners[i], second.corners[j], first.ids[i], second.ids[j])) {
        return true;
      }
    }
  }
  return false;
}

std::optional<std::string> fill_defect(const Mesh& mesh, const MeshTopology& topology,
                                       const Fill& fill, const Vec3* viewer) {
  const int boundary_size = static_cast<int>(fill.boundary.size());
  auto position = [&](int id) -> const Vec3& {
    return id < boundary_size ? mesh.positions[fill.boundary[id]] : fill.points[id - boundary_size];
  };
  std::map<std::pair<int, int>, int> directed;
  for (const Triangle& t : fill.triangles) {
    const Vec3 cross = (position(t[1]) - position(t[0])).cross(position(t[2]) - position(t[0]));
    if (!(cross.norm() > 0) || (viewer && !(cross.dot(*viewer) > 0))) {
      return "a triangle is degenerate or flipped";
    }
    for (int k = 0; k < 3; ++k) {
      if (++directed[{t[k], t[(k + 1) % 3]}] > 1) return "an edge is used twice in one direction";
    }
  }
  for (const auto& [edge, count] : directed) {
    const auto [a, b] = edge;
    const bool reverse_present = directed.count({b, a}) > 0;
    const bool along_loop = a < boundary_size && b < boundary_size &&
                            (b + 1) % boundary_size == a;  // the loop runs b → a
    if (along_loop == reverse_present) {
      return along_loop ? "a boundary edge is used twice" : "the fill has a border of its own";
    }
    if (a < boundary_size && b < boundary_size && !along_loop && (a + 1) % boundary_size != b &&
        a < b && has_edge(mesh, topology, fill.boundary[a], fill.boundary[b])) {
      return "a chord duplicates an existing mesh edge";
    }
  }
  for (int i = 0; i < boundary_size; ++i) {
    if (!directed.count({(i + 1) % boundary_size, i})) return "a boundary edge is not covered";
  }
  return std::nullopt;
}

}  // namespace rangefill
