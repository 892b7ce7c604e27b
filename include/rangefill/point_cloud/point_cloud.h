// Point clouds: meshing an unorganised cloud before its holes are repaired. Wang & Oliveira
// (Section 4.1) mesh their clouds with the projection-based triangulation of Gopi & Krishnan, which
// PCL implements as GreedyProjectionTriangulation.
#pragma once

#include <string>
#include <vector>

#include "rangefill/core/mesh.h"

namespace rangefill {

/// How a file with points and no faces is turned into a mesh.
enum class Mesher { none, greedy };

/// "none", "greedy"; throws InvalidInput otherwise.
Mesher mesher_from_name(const std::string& name);
std::string mesher_name(Mesher mesher);

/// The greedy projection's parameters, lengths in units of the cloud's mean point spacing s
/// (mean_point_spacing), so that one set serves clouds of any scale.
struct GreedyMeshingOptions {
  double search_radius = 8;       // neighbours are looked for within this many s (setSearchRadius)
  double mu = 3;                  // ... and within mu × the distance to the nearest one (setMu)
  int max_neighbours = 100;       // setMaximumNearestNeighbors
  double max_surface_angle = 45;  // degrees between the normals of points that may be joined
  double min_angle = 10;          // degrees, triangle angles (setMinimumAngle)
  double max_angle = 120;         // degrees (setMaximumAngle)
  int normal_neighbours = 16;     // k of the normal estimation, for clouds without normals
};

/// The mean distance from each point to its nearest other point (PCL kd-tree); 0 for fewer than two
/// points.
double mean_point_spacing(const std::vector<Vec3>& points);

/// Triangulates a point cloud. `cloud` holds vertices and no faces; its positions, colours,
/// normals, extra properties and provenance come back bit for bit and in order. The triangles are
/// the greedy projection's, made an oriented manifold: a triangle that would be the third on an
/// edge, repeats one or has no area is left out; each connected piece is oriented consistently and
/// along the points' normals (the cloud's own, else estimated from `normal_neighbours` neighbours
/// and turned away from the centroid); then, until none is left, triangles folded over their
/// neighbours, both triangles of an edge that a twisted band runs the same way, and the smaller
/// fans of pinched vertices are dropped. What is dropped leaves small holes for the repair. Points
/// the triangulation leaves out stay, unreferenced. The triangles are the input's for a later
/// repair (provenance kOriginal). Silences PCL's console messages (pcl::console verbosity, process
/// wide). Throws InvalidInput if the cloud has faces or fewer than three points, or an option is
/// out of range; ProcessingError if no triangle comes out.
Mesh mesh_point_cloud(const Mesh& cloud, const GreedyMeshingOptions& options = {});

}  // namespace rangefill
