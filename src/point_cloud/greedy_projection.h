// Internal: the point-cloud meshing's PCL stages, normal estimation (pcl_features) and the greedy
// projection (pcl_surface, which loads VTK and its many shared libraries at every start of a
// program linked to it). They live in a module of their own, librangefill_greedy.so, installed
// beside librangefill.so, which repair/point_cloud.cpp loads (dlopen) when it first meshes a
// cloud. Not installed.
#pragma once

#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/point_cloud/point_cloud.h"

namespace rangefill::greedy_projection {

constexpr const char* kModule = "librangefill_greedy.so";
constexpr const char* kEntry = "rangefill_greedy_projection";

/// The module's entry: `triangles` receives the greedy projection's triangles of `points` (Gopi &
/// Krishnan), lengths in units of `spacing` (mean_point_spacing). `normals` are the points' own,
/// or empty: then they are estimated from options.normal_neighbours neighbours, turned away from
/// the centroid, and returned there.
using Entry = void (*)(const std::vector<Vec3>& points, std::vector<Vec3>& normals, double spacing,
                       const GreedyMeshingOptions& options, std::vector<Triangle>& triangles);

}  // namespace rangefill::greedy_projection
