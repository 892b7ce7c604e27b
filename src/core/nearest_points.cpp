#include "core/nearest_points.h"

#include <algorithm>

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>
#include <boost/iterator/counting_iterator.hpp>

namespace rangefill {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using PointMap = CGAL::Pointer_property_map<Point>::type;
// The tree holds indices into the points, read through the property map.
using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, CGAL::Search_traits_3<Kernel>>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;

}  // namespace

struct NearestPoints::Tree {
  std::vector<Point> points;
  std::unique_ptr<Search::Tree> tree;
};

NearestPoints::NearestPoints(const std::vector<Vec3>& points) : tree_(std::make_unique<Tree>()) {
  tree_->points.reserve(points.size());
  for (const Vec3& p : points) tree_->points.emplace_back(p.x(), p.y(), p.z());
  const PointMap map = CGAL::make_property_map(tree_->points);
  tree_->tree = std::make_unique<Search::Tree>(boost::counting_iterator<std::size_t>(0),
                                               boost::counting_iterator<std::size_t>(points.size()),
                                               Search::Tree::Splitter(), Traits(map));
  // Built now, not on the first query: queries may come from several threads.
  if (!points.empty()) tree_->tree->build();
}

NearestPoints::~NearestPoints() = default;
NearestPoints::NearestPoints(NearestPoints&&) noexcept = default;
NearestPoints& NearestPoints::operator=(NearestPoints&&) noexcept = default;

void NearestPoints::nearest(const Vec3& p, int k, std::vector<int>& indices,
                            std::vector<double>& squared_distances) const {
  indices.clear();
  squared_distances.clear();
  if (tree_->points.empty() || k <= 0) return;
  const auto count = static_cast<unsigned>(std::min<size_t>(k, tree_->points.size()));
  const Search search(*tree_->tree, Point(p.x(), p.y(), p.z()), count, 0, true,
                      Search::Distance(CGAL::make_property_map(tree_->points)));
  for (const auto& [index, squared] : search) {
    indices.push_back(static_cast<int>(index));
    squared_distances.push_back(squared);
  }
}

}  // namespace rangefill
