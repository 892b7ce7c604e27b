// Measuring a repair: distances between surfaces, closedness, edge ratio (self-intersections are
// core/intersection.h).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "rangefill/core/intersection.h"
#include "rangefill/core/mesh.h"

namespace rangefill {

/// Distances between two triangle sets, each given as a mesh and the faces to use.
struct SurfaceDistance {
  double hausdorff = 0;    // max of the two one-sided distances
  double from_first = 0;   // max over points of the first set of the distance to the second
  double from_second = 0;  // max over points of the second set of the distance to the first
  double mean = 0;         // the two one-sided mean distances (over each set's samples), averaged
};

/// Samples both sets (vertices and a barycentric grid no coarser than `spacing` on every triangle)
/// and measures exact point-to-triangle distances to the other set (CGAL AABB tree). Throws
/// InvalidInput if a set is empty or spacing is not positive.
SurfaceDistance surface_distance(const Mesh& first, const std::vector<int>& first_faces,
                                 const Mesh& second, const std::vector<int>& second_faces,
                                 double spacing);

/// The distance from each of `points` to the nearest of `faces` of `mesh` (exact point-to-triangle
/// distances, CGAL AABB tree). Throws InvalidInput if `faces` is empty.
std::vector<double> distances_to_faces(const std::vector<Vec3>& points, const Mesh& mesh,
                                       const std::vector<int>& faces);

/// Whether a mesh is a closed, consistently oriented 2-manifold, and why not.
struct ManifoldCheck {
  int boundary_loops = 0;
  int nonmanifold_edges = 0;
  int misoriented_edges = 0;
  int nonmanifold_vertices = 0;
  bool closed_manifold() const {
    return boundary_loops == 0 && nonmanifold_edges == 0 && misoriented_edges == 0 &&
           nonmanifold_vertices == 0;
  }
};
ManifoldCheck check_manifold(const Mesh& mesh);

/// Mean length of the unique edges of `faces` (the edge ratio r of Table 8 divides it by d_m).
double mean_edge_length(const Mesh& mesh, const std::vector<int>& faces);

/// The smallest corner angle of `faces`, in degrees (180 for no face).
double smallest_angle_degrees(const Mesh& mesh, const std::vector<int>& faces);

/// The faces whose provenance is `hole` (or every generated face for kAnyHole).
inline constexpr int kAnyHole = -2;
std::vector<int> faces_of_hole(const Mesh& mesh, int hole);

}  // namespace rangefill
