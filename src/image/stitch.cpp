// Stitching with CGAL's constrained Delaunay triangulation (2D).
#include "rangefill/image/stitch.h"

#include <algorithm>
#include <deque>
#include <limits>
#include <map>
#include <set>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "rangefill/core/errors.h"
#include "rangefill/core/geometry2d.h"

namespace rangefill {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using FaceInfoBase = CGAL::Triangulation_face_base_with_info_2<int, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceInfoBase>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt =
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_tag>;

// Nesting depth of every face: 0 outside all constraints, +1 across each constrained edge.
void mark_nesting(Cdt& cdt) {
  for (Cdt::Face_handle face : cdt.all_face_handles()) face->info() = -1;
  std::deque<Cdt::Face_handle> next_level{cdt.infinite_face()};
  for (int level = 0; !next_level.empty(); ++level) {
    std::deque<Cdt::Face_handle> queue;
    queue.swap(next_level);
    while (!queue.empty()) {
      const Cdt::Face_handle face = queue.front();
      queue.pop_front();
      if (face->info() != -1) continue;
      face->info() = level;
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle neighbour = face->neighbor(i);
        if (neighbour->info() != -1) continue;
        (cdt.is_constrained(Cdt::Edge(face, i)) ? next_level : queue).push_back(neighbour);
      }
    }
  }
}

// T1 without the triangles that reach the boundary `polygon`: they would cross its constraints.
std::vector<Triangle> triangles_clear_of(const std::vector<Triangle>& grid,
                                         const std::vector<Vec2>& planar,
                                         const std::vector<Vec2>& polygon) {
  const int boundary_size = static_cast<int>(polygon.size());
  std::vector<Triangle> kept;
  for (const Triangle& t : grid) {
    bool crosses = false;
    for (int k = 0; k < 3 && !crosses; ++k) {
      const Vec2 &a = planar[t[k]], &b = planar[t[(k + 1) % 3]];
      for (int i = 0; i < boundary_size && !crosses; ++i) {
        crosses = segments_touch(a, b, polygon[i], polygon[(i + 1) % boundary_size]);
      }
    }
    if (!crosses) kept.push_back(t);
  }
  return kept;
}

// The fill of `triangles` over fill-vertex ids (the hole's vertices, then every patch point):
// the points no triangle uses are dropped, the others renumbered in order of first use.
Fill compact_fill(const BoundaryLoop& hole, const Patch& patch, std::vector<Triangle> triangles) {
  const int boundary_size = static_cast<int>(hole.vertices.size());
  Fill fill;
  fill.boundary = hole.vertices;
  std::vector<int> new_id(patch.points.size(), -1);
  for (Triangle& t : triangles) {
    for (int& id : t) {
      if (id < boundary_size) continue;
      int& mapped = new_id[id - boundary_size];
      if (mapped < 0) {
        mapped = boundary_size + static_cast<int>(fill.points.size());
        fill.points.push_back(patch.points[id - boundary_size]);
        if (!patch.colors.empty()) fill.colors.push_back(patch.colors[id - boundary_size]);
      }
      id = mapped;
    }
  }
  fill.triangles = std::move(triangles);
  return fill;
}

}  // namespace

std::vector<Triangle> triangulate_grid(const Patch& patch) {
  std::vector<Triangle> triangles;
  const cv::Mat& index = patch.index;
  for (int row = 0; row + 1 < index.rows; ++row) {
    for (int col = 0; col + 1 < index.cols; ++col) {
      const int top_left = index.at<int>(row, col), top_right = index.at<int>(row, col + 1);
      const int bottom_left = index.at<int>(row + 1, col),
                bottom_right = index.at<int>(row + 1, col + 1);
      // Eq. 15 with the diagonal bottom-left – top-right; counter-clockwise with y up (rows down).
      const bool upper = top_left >= 0 && top_right >= 0 && bottom_left >= 0;
      const bool lower = top_right >= 0 && bottom_left >= 0 && bottom_right >= 0;
      if (upper) triangles.push_back({top_left, bottom_left, top_right});
      if (lower) triangles.push_back({top_right, bottom_left, bottom_right});
      if (upper || lower) continue;
      // Three pixels present without that diagonal: split by the other one.
      if (top_left >= 0 && bottom_left >= 0 && bottom_right >= 0) {
        triangles.push_back({top_left, bottom_left, bottom_right});
      } else if (top_left >= 0 && top_right >= 0 && bottom_right >= 0) {
        triangles.push_back({top_left, bottom_right, top_right});
      }
    }
  }
  return triangles;
}

FillOutcome stitch(const Mesh& mesh, const MeshTopology& topology, const BoundaryLoop& hole,
                   const HoleInPlane& plane, const Patch& patch,
                   const std::vector<Triangle>& grid) {
  const Frame& frame = plane.frame;
  const std::vector<Vec2>& polygon = plane.loop;
  const int boundary_size = static_cast<int>(polygon.size());
  std::vector<Vec2> planar;
  for (const Vec3& p : patch.points) planar.push_back(frame.to_local(p).head<2>());

  const std::vector<Triangle> kept = triangles_clear_of(grid, planar, polygon);

  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles;
  // False when the point falls on one inserted before.
  auto insert = [&](const Vec2& p, int id) {
    const size_t before = cdt.number_of_vertices();
    Cdt::Vertex_handle handle = cdt.insert(Cdt::Point(p.x(), p.y()));
    if (cdt.number_of_vertices() == before) return false;
    handle->info() = id;
    handles.push_back(handle);
    return true;
  };
  bool distinct = true;
  for (int i = 0; i < boundary_size && distinct; ++i) distinct = insert(polygon[i], i);
  for (size_t k = 0; k < planar.size() && distinct; ++k) {
    distinct = insert(planar[k], boundary_size + static_cast<int>(k));
  }
  if (!distinct) return Refused{Refusal::not_manifold, "stitching: two points project onto one"};

  std::map<std::pair<int, int>, int> grid_edges;
  for (const Triangle& t : kept) {
    for (int k = 0; k < 3; ++k) ++grid_edges[{t[k], t[(k + 1) % 3]}];
  }
  try {
    for (int i = 0; i < boundary_size; ++i) {
      cdt.insert_constraint(handles[i], handles[(i + 1) % boundary_size]);
    }
    for (const auto& [edge, count] : grid_edges) {
      if (!grid_edges.count({edge.second, edge.first})) {
        cdt.insert_constraint(handles[boundary_size + edge.first],
                              handles[boundary_size + edge.second]);
      }
    }
  } catch (const Cdt::Intersection_of_constraints_exception&) {
    return Refused{Refusal::not_manifold, "stitching: the grid border crosses the hole boundary"};
  }
  mark_nesting(cdt);

  // T1 ∪ T2 over fill-vertex ids (points not yet compacted).
  std::vector<Triangle> triangles;
  for (const Triangle& t : kept) {
    triangles.push_back({boundary_size + t[0], boundary_size + t[1], boundary_size + t[2]});
  }
  for (Cdt::Face_handle face : cdt.finite_face_handles()) {
    if (face->info() % 2 == 1) {
      triangles.push_back(
          {face->vertex(0)->info(), face->vertex(1)->info(), face->vertex(2)->info()});
    }
  }

  const Fill fill = compact_fill(hole, patch, std::move(triangles));
  const Vec3 viewer = frame.normal();
  if (const auto defect = fill_defect(mesh, topology, fill, &viewer)) {
    return Refused{Refusal::not_manifold, "stitching: " + *defect};
  }
  return fill;
}

}  // namespace rangefill
