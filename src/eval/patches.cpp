#include "rangefill/eval/patches.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <opencv2/imgproc.hpp>

#include "rangefill/core/topology.h"
#include "rangefill/eval/punch.h"
#include "rangefill/hole/holes.h"
#include "rangefill/image/range_image.h"

namespace rangefill {

namespace {

// Uniform in [0, 1) from 53 random bits: the same on every standard library.
double uniform01(std::mt19937_64& random) {
  return (random() >> 11) * 0x1.0p-53;
}

// The faces connected to `centre`'s through shared edges whose corners all lie within `reach`.
Zone faces_around(const Mesh& mesh, const MeshTopology& topology, int centre, double reach) {
  const Vec3& c = mesh.positions[centre];
  auto near = [&](int face) {
    const Triangle& t = mesh.triangles[face];
    return std::all_of(t.begin(), t.end(),
                       [&](int v) { return (mesh.positions[v] - c).norm() <= reach; });
  };
  std::vector<char> seen(mesh.face_count(), 0);
  std::vector<int> faces;
  for (int face : faces_of_vertex(topology, centre)) {
    if (!seen[face] && near(face)) {
      seen[face] = 1;
      faces.push_back(face);
    }
  }
  for (size_t k = 0; k < faces.size(); ++k) {
    for (int corner = 0; corner < 3; ++corner) {
      const int opposite = topology.opposite[3 * faces[k] + corner];
      if (opposite < 0) continue;
      const int neighbour = halfedge_face(opposite);
      if (!seen[neighbour] && near(neighbour)) {
        seen[neighbour] = 1;
        faces.push_back(neighbour);
      }
    }
  }
  Zone zone;
  std::sort(faces.begin(), faces.end());
  zone.faces = faces;
  for (int face : faces) {
    for (int v : mesh.triangles[face]) zone.vertices.push_back(v);
  }
  std::sort(zone.vertices.begin(), zone.vertices.end());
  zone.vertices.erase(std::unique(zone.vertices.begin(), zone.vertices.end()), zone.vertices.end());
  return zone;
}

}  // namespace

std::vector<DepthPatch> depth_patches(const Mesh& mesh, const PatchOptions& options) {
  std::vector<DepthPatch> patches;
  if (mesh.vertex_count() == 0) return patches;
  const MeshTopology topology = build_topology(mesh);
  const double mean_edge = mean_edge_length(mesh, topology);
  const double step = options.beta * mean_edge;
  const double reach = (options.size / 2.0 + 3) * step * std::sqrt(2.0);
  RangeImageOptions image_options;
  image_options.beta = options.beta;
  std::mt19937_64 random(options.seed);
  for (int attempt = 0; attempt < options.count * options.attempts &&
                        static_cast<int>(patches.size()) < options.count;
       ++attempt) {
    const int centre = static_cast<int>(random() % static_cast<std::uint64_t>(mesh.vertex_count()));
    const Zone zone = faces_around(mesh, topology, centre, reach);
    Vec3 normal = Vec3::Zero();
    for (int face : zone.faces) normal += triangle_cross(mesh, face);
    if (!(normal.norm() > 0)) continue;
    normal.normalize();
    Frame frame;
    const Vec3 u = normal.unitOrthogonal();
    frame.rotation.row(0) = u.transpose();
    frame.rotation.row(1) = normal.cross(u).transpose();
    frame.rotation.row(2) = normal.transpose();
    frame.origin = mesh.positions[centre];
    RangeImage image = rasterize_zone(mesh, zone, BoundaryLoop{}, HoleInPlane{frame, {}}, mean_edge,
                                      image_options);
    fill_small_gaps(image);
    const int col = static_cast<int>(std::lround(-image.x_min / image.step)) - options.size / 2;
    const int row = static_cast<int>(std::lround(image.y_max / image.step)) - options.size / 2;
    const cv::Rect crop(col, row, options.size, options.size);
    if ((crop & cv::Rect(0, 0, image.depth.cols, image.depth.rows)) != crop) continue;
    const cv::Mat seen = image.labels(crop) == kKnownPixel;
    if (seen.total() - cv::countNonZero(seen) > options.max_unseen * seen.total()) continue;
    patches.push_back({image.depth(crop).clone(), seen, 1 / (image.depth_scale * mean_edge)});
  }
  return patches;
}

cv::Mat blob_mask(cv::Size size, double min_fraction, double max_fraction, int margin,
                  std::uint64_t seed) {
  std::mt19937_64 random(seed);
  const double target = min_fraction + (max_fraction - min_fraction) * uniform01(random);
  const int blobs = 1 + static_cast<int>(random() % 4);
  struct Blob {
    cv::Point2d centre;
    cv::Size2d axes;
    double angle;
  };
  std::vector<Blob> shapes;
  const cv::Rect inner(margin, margin, size.width - 2 * margin, size.height - 2 * margin);
  for (int b = 0; b < blobs; ++b) {
    shapes.push_back({{inner.x + inner.width * (0.25 + 0.5 * uniform01(random)),
                       inner.y + inner.height * (0.25 + 0.5 * uniform01(random))},
                      {0.5 + uniform01(random), 0.5 + uniform01(random)},
                      360 * uniform01(random)});
  }
  // Grow the blobs together until they cover the target share (clipped to the inner rectangle).
  cv::Mat mask;
  for (double scale = 1; scale < std::max(size.width, size.height); scale *= 1.05) {
    mask = cv::Mat::zeros(size, CV_8U);
    for (const Blob& blob : shapes) {
      cv::ellipse(mask, cv::RotatedRect(blob.centre, blob.axes * scale, blob.angle),
                  cv::Scalar(255), cv::FILLED);
    }
    cv::Mat outside = cv::Mat::ones(size, CV_8U) * 255;
    outside(inner) = 0;
    mask.setTo(0, outside);
    if (cv::countNonZero(mask) >= target * size.area()) break;
  }
  return mask;
}

HoleSample make_hole_sample(const DepthPatch& patch, const cv::Mat& mask, TrendKind trend,
                            double ring) {
  cv::Mat labels(patch.depth.size(), CV_8U, cv::Scalar(kOutsidePixel));
  labels.setTo(kKnownPixel, patch.seen);
  labels.setTo(kHolePixel, mask);
  HoleSample sample;
  cv::Mat residual =
      patch.depth - fit_trend(patch.depth, labels, trend, ring).image(patch.depth.size());
  residual.convertTo(sample.truth, CV_64F);
  sample.mask = mask.clone();
  sample.mean_edges_per_unit = patch.mean_edges_per_unit;
  return sample;
}

std::vector<HoleSample> hole_samples(const Mesh& mesh, const std::string& name,
                                     const HoleSampleOptions& options) {
  PatchOptions patch_options = options.patches;
  patch_options.seed = seed_for_mesh(options.patches.seed, name);
  std::vector<HoleSample> samples;
  const std::vector<DepthPatch> patches = depth_patches(mesh, patch_options);
  for (size_t p = 0; p < patches.size(); ++p) {
    const cv::Mat mask = blob_mask(patches[p].depth.size(), options.min_hole, options.max_hole,
                                   options.margin, patch_options.seed + p) &
                         patches[p].seen;
    samples.push_back(make_hole_sample(patches[p], mask));
  }
  return samples;
}

double restoration_rmse(const HoleSample& sample, const Inpainter& inpainter) {
  cv::Mat input, restored;
  sample.truth.convertTo(input, CV_32F);
  input.setTo(0, sample.mask);
  inpainter.inpaint(input, sample.mask, restored);
  double sum = 0;
  int count = 0;
  for (int row = 0; row < restored.rows; ++row) {
    for (int col = 0; col < restored.cols; ++col) {
      if (!sample.mask.at<std::uint8_t>(row, col)) continue;
      const double error = restored.at<float>(row, col) - sample.truth.at<double>(row, col);
      sum += error * error;
      ++count;
    }
  }
  return count > 0 ? std::sqrt(sum / count) * sample.mean_edges_per_unit : 0;
}

}  // namespace rangefill
