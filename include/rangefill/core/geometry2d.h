// Small predicates in the plane, shared by the stages that work on projections.
#pragma once

#include <algorithm>
#include <vector>

#include <Eigen/Core>

namespace rangefill {

using Vec2 = Eigen::Vector2d;

/// Twice the signed area of the triangle (a, b, c): positive when counter-clockwise.
inline double orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

/// Whether the closed segments ab and cd share a point (touching and collinear overlaps included).
inline bool segments_touch(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  auto within_box = [](const Vec2& p, const Vec2& q, const Vec2& r) {
    return std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  const double o1 = orient2d(a, b, c), o2 = orient2d(a, b, d), o3 = orient2d(c, d, a),
               o4 = orient2d(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) {
    return true;
  }
  return (o1 == 0 && within_box(a, b, c)) || (o2 == 0 && within_box(a, b, d)) ||
         (o3 == 0 && within_box(c, d, a)) || (o4 == 0 && within_box(c, d, b));
}

/// Distance from p to the closed segment ab.
inline double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t =
      ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

/// Signed area of a closed polygon (shoelace), positive when counter-clockwise.
inline double polygon_area(const std::vector<Vec2>& polygon) {
  double twice = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    twice += orient2d(Vec2::Zero(), polygon[i], polygon[(i + 1) % polygon.size()]);
  }
  return twice / 2;
}

}  // namespace rangefill
