#include "rangefill/fillers/mls.h"

#include <cmath>

#include <Eigen/Dense>

#include "core/nearest_points.h"

namespace rangefill {

struct MlsSurface::Index {
  NearestPoints tree;
};

MlsSurface::MlsSurface(std::vector<Vec3> samples, std::vector<Vec3> normals,
                       const MlsOptions& options)
    : index_(std::make_unique<Index>(Index{NearestPoints({})})),
      samples_(std::move(samples)),
      normals_(std::move(normals)),
      options_(options) {
  add_samples({}, {});
}

void MlsSurface::add_samples(const std::vector<Vec3>& samples, const std::vector<Vec3>& normals) {
  samples_.insert(samples_.end(), samples.begin(), samples.end());
  if (!normals_.empty()) normals_.insert(normals_.end(), normals.begin(), normals.end());
  index_->tree = NearestPoints(samples_);
}

MlsSurface::~MlsSurface() = default;
MlsSurface::MlsSurface(MlsSurface&&) noexcept = default;

size_t MlsSurface::size() const {
  return samples_.size();
}

void MlsSurface::neighbourhood(const Vec3& p, const Vec3& facing, std::vector<int>& indices,
                               double& h) const {
  indices.clear();
  h = 0;
  if (samples_.empty()) return;
  std::vector<double> squared;
  index_->tree.nearest(p, options_.neighbours, indices, squared);
  if (!normals_.empty() && facing.squaredNorm() > 0) {
    std::vector<int> facing_indices;
    for (int i : indices) {
      if (normals_[i].dot(facing) > 0) facing_indices.push_back(i);
    }
    if (facing_indices.size() >= 6) indices = std::move(facing_indices);
  }
  for (int i : indices) h = std::max(h, (samples_[i] - p).norm());
  h = std::max(h * options_.bandwidth, 1e-12);
}

namespace {

double gaussian(double distance, double h) {
  return std::exp(-(distance * distance) / (h * h));
}

}  // namespace

ReferencePlane MlsSurface::reference_plane(const Vec3& r, const Vec3& facing) const {
  std::vector<int> indices;
  double h = 0;
  neighbourhood(r, facing, indices, h);
  ReferencePlane plane;
  plane.origin = r;
  if (indices.size() < 3) return plane;
  Vec3 orientation = Vec3::Zero();
  for (int i : indices) {
    if (!normals_.empty()) orientation += normals_[i];
  }
  Vec3 q = r;
  for (int iteration = 0; iteration < options_.plane_iterations; ++iteration) {
    double total = 0;
    Vec3 centroid = Vec3::Zero();
    for (int i : indices) {
      const double w = gaussian((samples_[i] - q).norm(), h);
      centroid += w * samples_[i];
      total += w;
    }
    if (!(total > 0)) break;
    centroid /= total;
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (int i : indices) {
      const Vec3 d = samples_[i] - centroid;
      covariance += gaussian((samples_[i] - q).norm(), h) * d * d.transpose();
    }
    Vec3 n = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(0);
    if (n.dot(orientation.norm() > 0 ? orientation : plane.normal) < 0) n = -n;
    plane.normal = n.normalized();
    q = r + plane.normal.dot(centroid - r) * plane.normal;  // r + t·n
  }
  plane.origin = q;
  plane.u = plane.normal.unitOrthogonal();
  plane.v = plane.normal.cross(plane.u);
  return plane;
}

std::optional<MlsProjection> MlsSurface::project(const Vec3& r, const Vec3& facing) const {
  std::vector<int> indices;
  double h = 0;
  neighbourhood(r, facing, indices, h);
  if (indices.size() < 3) return std::nullopt;
  const ReferencePlane plane = reference_plane(r, facing);
  MlsProjection projection{plane.origin, plane.normal};
  if (indices.size() < 6) return projection;

  // g(x, y) = a0 + a1 x + a2 y + a3 x² + a4 x y + a5 y², weighted by θ(‖p_i − q‖).
  Eigen::MatrixXd a(indices.size(), 6);
  Eigen::VectorXd b(indices.size());
  for (size_t k = 0; k < indices.size(); ++k) {
    const Vec3& p = samples_[indices[k]];
    const Eigen::Vector2d xy = plane.to_plane(p) / h;  // scaled for conditioning
    const double w = std::sqrt(gaussian((p - plane.origin).norm(), h));
    a.row(k) << w, w * xy.x(), w * xy.y(), w * xy.x() * xy.x(), w * xy.x() * xy.y(),
        w * xy.y() * xy.y();
    b[k] = w * plane.normal.dot(p - plane.origin) / h;
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < 6) return projection;
  const Eigen::Matrix<double, 6, 1> c = qr.solve(b);
  projection.point = plane.origin + c[0] * h * plane.normal;
  projection.normal = (plane.normal - c[1] * plane.u - c[2] * plane.v).normalized();
  return projection;
}

}  // namespace rangefill
