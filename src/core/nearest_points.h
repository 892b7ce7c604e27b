// Internal: the k nearest of a set of points, in CGAL's kd-tree (header-only, so that no program
// loads a library for it at start-up).
#pragma once

#include <memory>
#include <vector>

#include "rangefill/core/mesh.h"

namespace rangefill {

/// A fixed set of points for nearest-neighbour queries. Queries are const and may run from
/// several threads.
class NearestPoints {
 public:
  explicit NearestPoints(const std::vector<Vec3>& points);
  ~NearestPoints();
  NearestPoints(NearestPoints&&) noexcept;
  NearestPoints& operator=(NearestPoints&&) noexcept;

  /// The indices of the min(k, size) points nearest to p, nearest first, and their squared
  /// distances to p.
  void nearest(const Vec3& p, int k, std::vector<int>& indices,
               std::vector<double>& squared_distances) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace rangefill
