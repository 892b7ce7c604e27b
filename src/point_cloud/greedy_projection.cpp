// The module librangefill_greedy.so (point_cloud/greedy_projection.h): the only translation unit
// that includes PCL's surface and feature modules.
#include "point_cloud/greedy_projection.h"

#include <cmath>

#include <pcl/console/print.h>

#include <pcl/features/normal_3d.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/gp3.h>

namespace rangefill::greedy_projection {

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// The points as a PCL cloud (single precision).
Cloud::Ptr to_cloud(const std::vector<Vec3>& points) {
  Cloud::Ptr cloud(new Cloud);
  cloud->reserve(points.size());
  for (const Vec3& p : points) {
    cloud->push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                   static_cast<float>(p.z())));
  }
  return cloud;
}

// PCL's normal estimate of each point, turned away from the centroid.
std::vector<Vec3> estimated_normals(const std::vector<Vec3>& points, const Cloud::Ptr& xyz,
                                    int neighbours) {
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  const pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  tree->setInputCloud(xyz);
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimation;
  estimation.setInputCloud(xyz);
  estimation.setSearchMethod(tree);
  estimation.setKSearch(neighbours);
  estimation.setViewPoint(static_cast<float>(centroid.x()), static_cast<float>(centroid.y()),
                          static_cast<float>(centroid.z()));
  pcl::PointCloud<pcl::Normal> estimated;
  estimation.compute(estimated);
  std::vector<Vec3> normals;
  normals.reserve(estimated.size());
  for (const pcl::Normal& n : estimated) {
    normals.push_back(-Vec3(n.normal_x, n.normal_y, n.normal_z));  // towards the viewpoint
  }
  return normals;
}

}  // namespace

}  // namespace rangefill::greedy_projection

extern "C" __attribute__((visibility("default"))) void rangefill_greedy_projection(
    const std::vector<rangefill::Vec3>& points, std::vector<rangefill::Vec3>& normals,
    double spacing, const rangefill::GreedyMeshingOptions& options,
    std::vector<rangefill::Triangle>& triangles) {
  using namespace rangefill;
  const greedy_projection::Cloud::Ptr xyz = greedy_projection::to_cloud(points);
  if (normals.empty()) {
    normals = greedy_projection::estimated_normals(points, xyz, options.normal_neighbours);
  }
  pcl::PointCloud<pcl::PointNormal>::Ptr oriented(new pcl::PointCloud<pcl::PointNormal>);
  oriented->reserve(xyz->size());
  for (size_t i = 0; i < xyz->size(); ++i) {
    pcl::PointNormal p;
    p.x = (*xyz)[i].x;
    p.y = (*xyz)[i].y;
    p.z = (*xyz)[i].z;
    const Vec3 n =
        normals[i].allFinite() && normals[i].norm() > 0 ? normals[i].normalized() : Vec3::UnitZ();
    p.normal_x = static_cast<float>(n.x());
    p.normal_y = static_cast<float>(n.y());
    p.normal_z = static_cast<float>(n.z());
    oriented->push_back(p);
  }
  pcl::search::KdTree<pcl::PointNormal>::Ptr tree(new pcl::search::KdTree<pcl::PointNormal>);
  tree->setInputCloud(oriented);
  // The library prints nothing; PCL's triangulation warns on the console unless told not to.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  pcl::GreedyProjectionTriangulation<pcl::PointNormal> greedy;
  greedy.setSearchRadius(options.search_radius * spacing);
  greedy.setMu(options.mu);
  greedy.setMaximumNearestNeighbors(options.max_neighbours);
  greedy.setMaximumSurfaceAngle(options.max_surface_angle * M_PI / 180);
  greedy.setMinimumAngle(options.min_angle * M_PI / 180);
  greedy.setMaximumAngle(options.max_angle * M_PI / 180);
  greedy.setNormalConsistency(false);
  greedy.setInputCloud(oriented);
  greedy.setSearchMethod(tree);
  std::vector<pcl::Vertices> polygons;
  greedy.reconstruct(polygons);
  triangles.clear();
  triangles.reserve(polygons.size());
  for (const pcl::Vertices& polygon : polygons) {
    if (polygon.vertices.size() != 3) continue;
    triangles.push_back({static_cast<int>(polygon.vertices[0]),
                         static_cast<int>(polygon.vertices[1]),
                         static_cast<int>(polygon.vertices[2])});
  }
}
