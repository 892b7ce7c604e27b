#include "rangefill/image/plane_filler.h"

#include <chrono>
#include <optional>

#include "rangefill/core/errors.h"
#include "rangefill/image/complex_hole.h"
#include "rangefill/image/stitch.h"
#include "rangefill/inpaint/inpainters.h"

namespace rangefill {

namespace {

using Clock = std::chrono::steady_clock;

// Seconds since `start`, which moves on to now.
double lap(Clock::time_point& start) {
  const Clock::time_point now = Clock::now();
  const double seconds = std::chrono::duration<double>(now - start).count();
  start = now;
  return seconds;
}

// The edges of `hole` that no face borders, in the frame's x, y: the chord closing a part of a
// complex hole (Section VI-C).
std::vector<std::array<Vec2, 2>> chords_in_plane(const SurfaceContext& surface,
                                                 const BoundaryLoop& hole,
                                                 const HoleInPlane& plane) {
  std::vector<std::array<Vec2, 2>> chords;
  const size_t n = hole.vertices.size();
  for (size_t k = 0; k < n; ++k) {
    if (find_halfedge(surface.mesh, surface.topology, hole.vertices[k],
                      hole.vertices[(k + 1) % n]) < 0) {
      chords.push_back({plane.loop[k], plane.loop[(k + 1) % n]});
    }
  }
  return chords;
}

// What the fillers of this file share: the options and the back-end.
class ImagePipeline {
 public:
  explicit ImagePipeline(const PlaneFillerOptions& options)
      : options_(options), inpainter_(make_inpainter(options.inpainter, options.inpainting)) {}

  // Sections VI–VIII on each plane in turn: the first fill accepted wins, the first refusal is
  // kept; no plane at all is a complex hole (VI-C).
  FillOutcome fill_through_planes(const HoleContext& context, const BoundaryLoop& hole,
                                  const Zone& zone, const std::vector<Projection>& planes,
                                  const AcceptFill& accept, FillerLog& log) const {
    std::optional<Refused> first;
    for (const Projection& projection : planes) {
      FillOutcome outcome = [&]() -> FillOutcome {
        try {
          return fill_through_plane(context, hole, zone, projection.plane, accept, log);
        } catch (const ProcessingError& error) {
          return Refused{Refusal::error, error.what()};
        }
      }();
      if (std::holds_alternative<Fill>(outcome)) return outcome;
      if (!first) first = std::get<Refused>(std::move(outcome));
    }
    if (first) return *first;
    return Refused{Refusal::no_plane, ""};
  }

  ProjectionSearch find_planes(const SurfaceContext& surface, const Zone& zone,
                               const BoundaryLoop& hole, FillerLog& log) const {
    Clock::time_point start = Clock::now();
    ProjectionSearch search =
        find_projections(surface.mesh, surface.topology, zone, hole, options_.projection);
    add_seconds(log.steps, "planes", lap(start));
    return search;
  }

 private:
  // Sections VI–VIII on one plane: range image, trend, inpainting, back-projection, stitching.
  FillOutcome fill_through_plane(const HoleContext& context, const BoundaryLoop& hole,
                                 const Zone& zone, const HoleInPlane& plane,
                                 const AcceptFill& accept, FillerLog& log) const {
    const SurfaceContext& surface = context.surface;
    const Mesh& mesh = surface.mesh;
    const MeshTopology& topology = surface.topology;
    Clock::time_point stage = Clock::now();
    const Zone visible = visible_part(mesh, topology, zone, hole, plane.frame);
    log.made_image = true;
    ImageFigures& figures = log.image;
    figures.visible_faces = static_cast<int>(visible.faces.size());

    RangeImage image =
        rasterize_zone(mesh, visible, hole, plane, surface.mean_edge, options_.image);
    figures.gap_pixels = fill_small_gaps(image).pixels;
    figures.rim_support = rim_support(image, chords_in_plane(surface, hole, plane));
    if (figures.rim_support < options_.min_rim_support) {
      add_seconds(log.steps, "image", lap(stage));
      return Refused{Refusal::partial_view,
                     "the plane sees only " +
                         std::to_string(static_cast<int>(100 * figures.rim_support)) +
                         "% of the hole's surroundings"};
    }
    const cv::Mat mask = image.mask();
    figures.width = image.depth.cols;
    figures.height = image.depth.rows;
    figures.masked_pixels = cv::countNonZero(mask);
    add_seconds(log.steps, "image", lap(stage));

    TrendKind fitted = TrendKind::none;
    const cv::Mat restored =
        inpaint_residual(image.depth, image.labels, mask, *inpainter_, options_.trend,
                         options_.trend_ring, 1 / (image.depth_scale * image.step), fitted);
    figures.trend = trend_name(fitted);
    const cv::Mat restored_color = image.color.empty() ? cv::Mat() : inpaint_colors(image, mask);
    add_seconds(log.steps, "inpainting", lap(stage));
    if (context.on_images) context.on_images({context.id, image, restored});

    stage = Clock::now();
    Patch patch = back_project(image, restored, options_.back_projection);
    if (!restored_color.empty()) patch.colors = patch_colors(patch, restored_color);
    FillOutcome stitched = stitch(mesh, topology, hole, plane, patch, triangulate_grid(patch));
    add_seconds(log.steps, "stitching", lap(stage));
    if (Fill* fill = std::get_if<Fill>(&stitched)) return accept(std::move(*fill));
    return stitched;
  }

  // Wang & Oliveira, Section 4.4: the colour channels inpainted as images, each like depth.
  cv::Mat inpaint_colors(const RangeImage& image, const cv::Mat& mask) const {
    std::vector<cv::Mat> channels;
    cv::split(image.color, channels);
    for (cv::Mat& channel : channels) {
      TrendKind fitted = TrendKind::none;
      channel = inpaint_residual(channel, image.labels, mask, *inpainter_, options_.trend,
                                 options_.trend_ring, 0, fitted);
    }
    cv::Mat color;
    cv::merge(channels, color);
    return color;
  }

  PlaneFillerOptions options_;
  std::unique_ptr<Inpainter> inpainter_;
};

class PlaneFiller : public Filler {
 public:
  PlaneFiller(std::string name, const PlaneFillerOptions& options)
      : name_(std::move(name)), pipeline_(options) {}
  std::string name() const override { return name_; }
  std::string method() const override { return "plane"; }
  FillOutcome fill(const HoleContext& context, const AcceptFill& accept,
                   FillerLog& log) const override {
    const ProjectionSearch search =
        pipeline_.find_planes(context.surface, context.zone, context.hole, log);
    return pipeline_.fill_through_planes(context, context.hole, context.zone, search.planes, accept,
                                         log);
  }

 private:
  std::string name_;
  ImagePipeline pipeline_;
};

class PlaneInPartFiller : public Filler {
 public:
  explicit PlaneInPartFiller(const PlaneFillerOptions& options) : pipeline_(options) {}
  std::string name() const override { return "plane-in-part"; }
  std::string method() const override { return "plane, in part"; }
  FillOutcome fill(const HoleContext& context, const AcceptFill& accept,
                   FillerLog& log) const override {
    const SurfaceContext& surface = context.surface;
    const HoleInPlane best = pipeline_.find_planes(surface, context.zone, context.hole, log).best;
    std::optional<Refused> first;
    for (const BoundaryLoop& part :
         split_complex_hole(surface.mesh, surface.topology, context.hole, best)) {
      const Zone zone = grow_zone(surface.mesh, surface.topology, surface.holes, part,
                                  surface.mean_edge, context.zone_options);
      const std::vector<Projection> planes = pipeline_.find_planes(surface, zone, part, log).planes;
      FillOutcome outcome = pipeline_.fill_through_planes(context, part, zone, planes, accept, log);
      if (std::holds_alternative<Fill>(outcome)) return outcome;
      if (!first) first = std::get<Refused>(std::move(outcome));
    }
    return Refused{Refusal::no_part, first ? refusal_text(first->refusal) : ""};
  }

 private:
  ImagePipeline pipeline_;
};

}  // namespace

std::shared_ptr<const Filler> make_plane_filler(const std::string& name,
                                                const PlaneFillerOptions& options) {
  return std::make_shared<PlaneFiller>(name, options);
}

std::shared_ptr<const Filler> make_plane_in_part_filler(const PlaneFillerOptions& options) {
  return std::make_shared<PlaneInPartFiller>(options);
}

}  // namespace rangefill
