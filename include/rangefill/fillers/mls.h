// The moving-least-squares projection operator (Levin; Alexa et al.; Tekumalla & Cohen, Section
// 2.1): a point near a sampled surface is projected onto the smooth surface the samples define.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "rangefill/core/mesh.h"

namespace rangefill {

struct MlsOptions {
  int neighbours = 32;       // samples used around each query (the k nearest)
  double bandwidth = 1.0;    // Gaussian width h, in units of the distance to the k-th neighbour
  int plane_iterations = 4;  // refinements of the reference plane
};

/// A local reference plane: origin q, unit normal n, tangent axes u, v (u × v = n).
struct ReferencePlane {
  Vec3 origin = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  Vec3 u = Vec3::UnitX();
  Vec3 v = Vec3::UnitY();
  Eigen::Vector2d to_plane(const Vec3& p) const { return {u.dot(p - origin), v.dot(p - origin)}; }
};

struct MlsProjection {
  Vec3 point;
  Vec3 normal;  // of the fitted quadratic at the point
};

/// The samples in a kd-tree (CGAL's) and the two steps of the operator. Queries are const and may
/// run from several threads.
class MlsSurface {
 public:
  /// `normals` (one per sample, or empty) only orient the reference planes consistently.
  MlsSurface(std::vector<Vec3> samples, std::vector<Vec3> normals, const MlsOptions& options = {});
  ~MlsSurface();
  MlsSurface(MlsSurface&&) noexcept;

  /// Adds samples (and their normals, if the surface has normals) and rebuilds the index.
  void add_samples(const std::vector<Vec3>& samples, const std::vector<Vec3>& normals);

  /// Step 1: the plane minimising Σ ⟨n, p_i − r − t n⟩² θ(‖p_i − r − t n‖) (Gaussian θ), found by
  /// alternating the weighted principal axis and the weighted centroid from q = r. Oriented along
  /// the nearby sample normals when there are any. With a `facing` direction, samples whose normal
  /// points away from it are left out (the other side of a thin part), unless too few remain.
  ReferencePlane reference_plane(const Vec3& r, const Vec3& facing = Vec3::Zero()) const;

  /// Step 2: a bivariate quadratic fitted by weighted least squares to the samples' heights over
  /// the plane, evaluated at the plane origin. Falls back to the plane itself when the fit is
  /// ill-conditioned; nullopt when there are fewer than three samples.
  std::optional<MlsProjection> project(const Vec3& r, const Vec3& facing = Vec3::Zero()) const;

  size_t size() const;

 private:
  struct Index;
  std::unique_ptr<Index> index_;
  std::vector<Vec3> samples_;
  std::vector<Vec3> normals_;
  MlsOptions options_;

  // The k nearest samples to p that face `facing` (all when it is zero or too few do), and the
  // Gaussian width h.
  void neighbourhood(const Vec3& p, const Vec3& facing, std::vector<int>& indices, double& h) const;
};

}  // namespace rangefill
