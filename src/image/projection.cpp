#include "rangefill/image/projection.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_set>

#include <Eigen/Eigenvalues>

namespace rangefill {

namespace {

struct Scored {
  Vec3 direction;
  double score;  // projected minus twice folded area, i.e. n·Σa − folded
  double projected;
  double folded;
};

Scored score_direction(const std::vector<Vec3>& area_vectors, const Vec3& n) {
  Scored s{n, 0, 0, 0};
  for (const Vec3& a : area_vectors) {
    const double along = n.dot(a);
    (along > 0 ? s.projected : s.folded) += std::abs(along);
  }
  s.score = s.projected - 2 * s.folded;
  return s;
}

// `count` directions spread evenly (Fibonacci spiral) over the spherical cap of half-angle `cap`
// around the unit vector `axis`.
std::vector<Vec3> cap_directions(const Vec3& axis, double cap, int count) {
  const Vec3 u = axis.unitOrthogonal();
  const Vec3 v = axis.cross(u);
  const double golden_angle = M_PI * (3 - std::sqrt(5.0));
  std::vector<Vec3> directions;
  for (int k = 0; k < count; ++k) {
    const double z = 1 - (1 - std::cos(cap)) * (k + 0.5) / count;
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    const double phi = k * golden_angle;
    directions.push_back((r * std::cos(phi) * u + r * std::sin(phi) * v + z * axis).normalized());
  }
  return directions;
}

// Local axes for viewing direction n: x along the main axis of the zone's projection.
Eigen::Matrix3d frame_axes(const Mesh& mesh, const Zone& zone, const Vec3& n) {
  const Vec3 u = n.unitOrthogonal();
  const Vec3 v = n.cross(u);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int vertex : zone.vertices)
    mean += Vec2(mesh.positions[vertex].dot(u), mesh.positions[vertex].dot(v));
  mean /= std::max<size_t>(1, zone.vertices.size());
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (int vertex : zone.vertices) {
    const Vec2 d = Vec2(mesh.positions[vertex].dot(u), mesh.positions[vertex].dot(v)) - mean;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(covariance);
  Vec2 main = solver.eigenvectors().col(1);
  Vec3 x = (main.x() * u + main.y() * v).normalized();
  int largest = 0;
  x.cwiseAbs().maxCoeff(&largest);
  if (x[largest] < 0) x = -x;  // a deterministic sign
  Eigen::Matrix3d rotation;
  rotation.row(0) = x.transpose();
  rotation.row(1) = n.cross(x).transpose();
  rotation.row(2) = n.transpose();
  return rotation;
}

}  // namespace

bool is_simple_polygon(const std::vector<Vec2>& polygon) {
  const size_t n = polygon.size();
  if (n < 3) return false;
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      if (polygon[i] == polygon[j]) return false;
    }
  }
  for (size_t i = 0; i < n; ++i) {
    const Vec2 &a = polygon[i], &b = polygon[(i + 1) % n];
    for (size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (segments_touch(a, b, polygon[j], polygon[(j + 1) % n])) return false;
    }
  }
  return true;
}

HoleInPlane hole_in_plane(const Mesh& mesh, const BoundaryLoop& hole, const Frame& frame) {
  HoleInPlane plane{frame, {}};
  plane.loop.reserve(hole.vertices.size());
  for (int v : hole.vertices) plane.loop.push_back(frame.to_local(mesh.positions[v]).head<2>());
  return plane;
}

// The faces on the hole boundary: those holding one of its half-edges (a chord closing a part
// of a complex hole has none).
static std::vector<int> boundary_faces(const Mesh& mesh, const MeshTopology& topology,
                                       const BoundaryLoop& hole) {
  std::vector<int> faces;
  const size_t n = hole.vertices.size();
  for (size_t k = 0; k < n; ++k) {
    const int h = find_halfedge(mesh, topology, hole.vertices[k], hole.vertices[(k + 1) % n]);
    if (h >= 0) faces.push_back(halfedge_face(h));
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

ProjectionSearch find_projections(const Mesh& mesh, const MeshTopology& topology, const Zone& zone,
                                  const BoundaryLoop& hole, const ProjectionOptions& options) {
  std::vector<Vec3> area_vectors;
  Vec3 vector_area = Vec3::Zero();
  for (int face : zone.faces) {
    area_vectors.push_back(0.5 * triangle_cross(mesh, face));
    vector_area += area_vectors.back();
  }
  // The hole's own vector area (the loop runs clockwise seen from the front, hence the minus).
  Vec3 loop_area = Vec3::Zero();
  for (size_t k = 0; k < hole.vertices.size(); ++k) {
    loop_area += mesh.positions[hole.vertices[k]].cross(
        mesh.positions[hole.vertices[(k + 1) % hole.vertices.size()]]);
  }
  loop_area *= -0.5;

  std::vector<Vec3> starts;
  for (const Vec3& candidate : {vector_area, loop_area}) {
    if (candidate.norm() > 0) starts.push_back(candidate.normalized());
  }
  if (zone.vertices.size() >= 3) {  // PCA: the axis of least spread
    Vec3 mean = Vec3::Zero();
    for (int v : zone.vertices) mean += mesh.positions[v];
    mean /= zone.vertices.size();
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (int v : zone.vertices) {
      const Vec3 d = mesh.positions[v] - mean;
      covariance += d * d.transpose();
    }
    Vec3 axis = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(0);
    if (axis.dot(starts.empty() ? Vec3::UnitZ() : starts.front()) < 0) axis = -axis;
    if (axis.allFinite() && axis.norm() > 0.5) starts.push_back(axis.normalized());
  }
  if (starts.empty()) starts.push_back(Vec3::UnitZ());

  std::vector<Scored> candidates;
  for (const Vec3& start : starts) candidates.push_back(score_direction(area_vectors, start));
  auto better = [](const Scored& a, const Scored& b) { return a.score > b.score; };
  Scored best = *std::max_element(candidates.begin(), candidates.end(),
                                  [&](const Scored& a, const Scored& b) { return better(b, a); });
  double cap = options.search_cap_degrees * M_PI / 180;
  for (int round = 0; round <= options.refinements; ++round) {
    for (const Vec3& direction : cap_directions(best.direction, cap, options.search_directions)) {
      candidates.push_back(score_direction(area_vectors, direction));
      if (better(candidates.back(), best)) best = candidates.back();
    }
    cap /= 2;
  }
  std::stable_sort(candidates.begin(), candidates.end(), better);

  ProjectionSearch search;
  Frame best_frame;
  best_frame.rotation = frame_axes(mesh, zone, candidates.front().direction);
  for (int v : hole.vertices) best_frame.origin += mesh.positions[v];
  best_frame.origin /= std::max<size_t>(1, hole.vertices.size());
  search.best = hole_in_plane(mesh, hole, best_frame);
  const std::vector<int> rim = boundary_faces(mesh, topology, hole);
  const double separation = std::cos(options.min_separation_degrees * M_PI / 180);
  for (const Scored& candidate : candidates) {
    if (static_cast<int>(search.planes.size()) == options.planes) break;
    const bool too_close =
        std::any_of(search.planes.begin(), search.planes.end(), [&](const Projection& p) {
          return p.plane.frame.normal().dot(candidate.direction) > separation;
        });
    if (too_close) continue;
    double rim_area = 0, rim_behind = 0;
    for (int face : rim) {
      const Vec3 cross = triangle_cross(mesh, face);
      rim_area += cross.norm();
      if (cross.dot(candidate.direction) <= 0) rim_behind += cross.norm();
    }
    if (rim_behind > options.max_rim_behind * rim_area) continue;
    if (search.orientations_tried++ == options.max_orientations) break;
    Frame frame = search.best.frame;
    frame.rotation = frame_axes(mesh, zone, candidate.direction);
    HoleInPlane plane = hole_in_plane(mesh, hole, frame);
    if (!is_simple_polygon(plane.loop)) continue;
    search.planes.push_back({std::move(plane), candidate.projected, candidate.folded});
  }
  return search;
}

Zone visible_part(const Mesh& mesh, const MeshTopology& topology, const Zone& zone,
                  const BoundaryLoop& hole, const Frame& frame) {
  const Vec3 view = frame.normal();
  auto faces_viewer = [&](int face) { return triangle_cross(mesh, face).dot(view) > 0; };
  std::unordered_set<int> zone_faces(zone.faces.begin(), zone.faces.end());
  std::unordered_set<int> reached;
  std::vector<int> stack;
  for (int face : boundary_faces(mesh, topology, hole)) {
    if (zone_faces.count(face) && faces_viewer(face) && reached.insert(face).second)
      stack.push_back(face);
  }
  while (!stack.empty()) {
    const int face = stack.back();
    stack.pop_back();
    for (int corner = 0; corner < 3; ++corner) {
      const int opposite = topology.opposite[3 * face + corner];
      if (opposite < 0) continue;
      const int neighbour = halfedge_face(opposite);
      if (zone_faces.count(neighbour) && faces_viewer(neighbour) &&
          reached.insert(neighbour).second) {
        stack.push_back(neighbour);
      }
    }
  }
  Zone visible = zone;
  visible.faces.assign(reached.begin(), reached.end());
  std::sort(visible.faces.begin(), visible.faces.end());
  std::vector<int> vertices;
  for (int face : visible.faces) {
    for (int v : mesh.triangles[face]) vertices.push_back(v);
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  visible.vertices = std::move(vertices);
  return visible;
}

}  // namespace rangefill
