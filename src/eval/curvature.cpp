#include "rangefill/eval/curvature.h"

#include <algorithm>
#include <cmath>

namespace rangefill {

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

double VertexCurvature::max_principal(int v) const {
  const double h = mean[v], k = gaussian[v];
  return std::abs(h) + std::sqrt(std::max(h * h - k, 0.0));
}

VertexCurvature vertex_curvature(const Mesh& mesh, const MeshTopology& topology) {
  const int n = mesh.vertex_count();
  VertexCurvature curvature;
  curvature.area.assign(n, 0.0);
  curvature.gaussian.assign(n, 0.0);
  curvature.mean.assign(n, 0.0);
  std::vector<double> angle_sum(n, 0.0);
  std::vector<Vec3> laplacian(n, Vec3::Zero()), normal(n, Vec3::Zero());
  for (int f = 0; f < mesh.face_count(); ++f) {
    const Triangle& t = mesh.triangles[f];
    const Vec3 p[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
    const Vec3 cross = (p[1] - p[0]).cross(p[2] - p[0]);
    if (is_degenerate(mesh, f)) continue;  // too thin to have angles
    const double area = 0.5 * cross.norm();
    double angle[3], cot[3];
    for (int i = 0; i < 3; ++i) {
      const Vec3 u = p[(i + 1) % 3] - p[i], w = p[(i + 2) % 3] - p[i];
      angle[i] = std::atan2(u.cross(w).norm(), u.dot(w));
      cot[i] = u.dot(w) / u.cross(w).norm();
    }
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      angle_sum[t[i]] += angle[i];
      normal[t[i]] += cross;
      // Edge (j, k) lies opposite corner i: its cotangent weight (Meyer et al., eq. 8).
      laplacian[t[j]] += cot[i] * (p[j] - p[k]);
      laplacian[t[k]] += cot[i] * (p[k] - p[j]);
      // Mixed area: the Voronoi part of a non-obtuse triangle, else halves and quarters (Fig. 4).
      if (angle[0] <= kPi / 2 && angle[1] <= kPi / 2 && angle[2] <= kPi / 2) {
        curvature.area[t[i]] +=
            ((p[i] - p[k]).squaredNorm() * cot[j] + (p[i] - p[j]).squaredNorm() * cot[k]) / 8;
      } else {
        curvature.area[t[i]] += angle[i] > kPi / 2 ? area / 2 : area / 4;
      }
    }
  }
  std::vector<char> on_border(n, 0);
  for (int h = 0; h < static_cast<int>(topology.opposite.size()); ++h) {
    if (topology.opposite[h] != kBoundary) continue;
    on_border[topology.halfedge_source(mesh, h)] = on_border[topology.halfedge_target(mesh, h)] = 1;
  }
  for (int v = 0; v < n; ++v) {
    const double a = curvature.area[v];
    if (!(a > 0)) continue;
    curvature.gaussian[v] = ((on_border[v] ? kPi : 2 * kPi) - angle_sum[v]) / a;
    const double h = laplacian[v].norm() / (4 * a);
    curvature.mean[v] = laplacian[v].dot(normal[v]) >= 0 ? h : -h;
  }
  return curvature;
}

std::vector<double> dihedral_angles(const Mesh& mesh, const MeshEdges& edges) {
  std::vector<double> angles(edges.edges.size(), 0.0);
  for (size_t e = 0; e < edges.edges.size(); ++e) {
    const Edge& edge = edges.edges[e];
    if (edge.count != 2) continue;
    const int f = halfedge_face(edges.edge_halfedges[edge.first]);
    const int g = halfedge_face(edges.edge_halfedges[edge.first + 1]);
    const Vec3 a = triangle_cross(mesh, f), b = triangle_cross(mesh, g);
    if (is_degenerate(mesh, f) || is_degenerate(mesh, g)) continue;
    angles[e] = std::atan2(a.cross(b).norm(), a.dot(b));
  }
  return angles;
}

}  // namespace rangefill
