// Depth maps: hole filling with the inpainting back-ends (fill_depth), depth image files, and what
// the depth benchmark is made of (a z-buffer renderer of meshes, sensor-like holes).
//
// Conventions: CV_16UC1 depth is in millimetres and CV_32FC1 depth in metres, both the distance
// along the optical axis (z, not the length of the ray). A pixel is invalid when its depth is 0,
// negative or not finite; 16-bit files hold 0 there, float files 0 or NaN.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "rangefill/inpainter.h"
#include "rangefill/mesh.h"
#include "rangefill/trend.h"

namespace rangefill {

/// The back-ends' options fill_depth takes by default: InpainterOptions' own, except that foe
/// refines Telea's fill by at most 10 steps, stopping earlier when one gains less than 3e-3 of E
/// (README, depth-bench: lower RMSE than the MAP from the harmonic start, 3–5 times faster).
InpainterOptions depth_inpainting_defaults();

struct DepthFillOptions {
  std::string inpainter = "harmonic";  // a name of inpainter_names()
  InpainterOptions inpainting = depth_inpainting_defaults();
  int threads = 1;                // holes filled at once; the result does not depend on it
  long long max_hole_pixels = 0;  // larger holes are left as they are; 0: no limit
  bool keep_border = false;       // leave holes that touch the image border as they are
  /// Depths z1 < z2 lie on different surfaces when z2 > (1 + discontinuity)·z1.
  double discontinuity = 0.05;
  /// Surface fitted to the valid pixels within `trend_ring` pixels of a hole, removed before the
  /// back-end and added back (trend.h). None by default: on depth maps the back-ends alone did
  /// better (README, depth-bench).
  TrendKind trend = TrendKind::none;
  double trend_ring = 3;
  int margin = 5;  // pixels around each hole given to the back-end (telea and ns read `radius`)
  /// Pixels farther than this from every pixel a hole is filled from take the depth of the
  /// nearest such pixel; the back-end restores the band within. 0: no limit.
  int reach = 32;
};

/// What fill_depth did. A hole is a connected component (8-neighbourhood) of the mask.
struct DepthFillStats {
  /// Holes left as they are for one reason, and their pixels.
  struct Left {
    int holes = 0;
    long long pixels = 0;
  };
  int holes = 0;
  int filled = 0;
  long long filled_pixels = 0;
  int at_edge = 0;       // filled holes beside an occluding edge (step 1 of fill_depth)
  Left too_large;        // more than max_hole_pixels
  Left at_border;        // touch the image border, and keep_border is set
  Left without_support;  // no valid pixel borders them
  cv::Mat filled_mask;   // CV_8UC1, the depth's size: 255 at the pixels this call filled

  int left_holes() const { return too_large.holes + at_border.holes + without_support.holes; }
  long long left_pixels() const {
    return too_large.pixels + at_border.pixels + without_support.pixels;
  }
};

/// Fills the holes of a depth map with an inpainting back-end, in the idiom of cv::inpaint.
///
/// `depth`: CV_16UC1 (millimetres) or CV_32FC1 (metres). `invalid_mask`: the pixels to fill,
/// CV_8UC1 of the same size, non-zero to fill (whatever their depth); empty (cv::noArray()) takes
/// every invalid pixel. `filled` receives an image of the depth's type and size: every pixel
/// outside the filled holes as given, bit for bit; 16-bit fills rounded to the millimetre. Invalid
/// pixels outside the mask are never read as data. Deterministic at any thread count. Throws
/// InvalidInput, with a one-line message, on a bad type or size, an unknown back-end or options
/// out of range (discontinuity ≤ 0, margin < 1, max_hole_pixels < 0, threads < 1).
///
/// Each hole (a connected component of the mask, 8-neighbourhood) is filled on its own, from a
/// window of `margin` pixels around it. Its rim is the valid pixels 8-adjacent to it. A hole that
/// touches the image border is filled like the others (unless keep_border): the back-ends treat
/// the border as a free edge, so the fill is extrapolated from the rim inside the image, under the
/// same occlusion rule. `stats.filled_mask` tells which pixels were filled; a hole is left only
/// for a reason counted in the stats (too large, at the border when asked, no valid rim).
///  1. Occluding edges. Looking across the hole from a rim pixel p in each of the 8 directions, the
///     first valid pixel q beyond the hole lies behind p when it is deeper by more than
///     `discontinuity` and p is nearer than q's surface continued to p by as much (q's local plane:
///     inverse depth fitted to its neighbours within 2 pixels on its surface). Then p occludes: it
///     is on the near side of a depth edge the hole hides. A steep continuous surface, such as a
///     floor at a grazing angle, continues to p and makes no edge.
///  2. Discontinuity rule: the background goes on behind an occluder, the occluder does not go on
///     into the hole. The hole is filled from the valid pixels whose nearest rim pixel does not
///     occlude and lies on their surface; occluding rim pixels and the occluder behind them are not
///     used. So a sensor shadow (a band between a near object and the background) is filled at the
///     background's depth, never by a ramp from near to far; so is a hole across an object's
///     silhouette, near part included, and a thin object crossing a hole is cut. A hole on a near
///     surface that reaches its silhouette keeps the rim pixels that see their own surface across.
///  3. The source pixels go to inverse depth 1/z, on which a plane of the scene is linear in the
///     pixel, normalised onto [0, 1] over the source (as eq. 7–8 do for range images), minus the
///     trend if any; the back-end restores the hole with every other pixel of the window masked;
///     the fill is clamped to the source's range widened by half on either side.
DepthFillStats fill_depth(cv::InputArray depth, cv::InputArray invalid_mask, cv::OutputArray filled,
                          const DepthFillOptions& options = {});

/// The pixels fill_depth reads as invalid: CV_8UC1, 255 where depth (CV_16UC1 or CV_32FC1) is 0,
/// negative or not finite.
cv::Mat invalid_depth_mask(cv::InputArray depth);

/// Reads a depth image: 16-bit PNG or TIFF (CV_16UC1, millimetres), float TIFF or EXR (CV_32FC1,
/// metres), one channel. Throws IoError when the file cannot be read, InvalidInput when it is not
/// such an image; the message names the file.
cv::Mat read_depth_image(const std::filesystem::path& path);

/// Reads a mask image of any depth, one channel: CV_8UC1, 255 where the file is non-zero.
cv::Mat read_mask_image(const std::filesystem::path& path);

/// Writes a mask (CV_8UC1) as an 8-bit PNG or TIFF, by the extension, atomically. Throws
/// InvalidInput (another type or extension) or IoError, naming the file.
void write_mask_image(const cv::Mat& mask, const std::filesystem::path& path);

/// True when the extension of `path` (any case) is one of the depth image formats: .png, .tif,
/// .tiff, .exr.
bool is_depth_image_path(const std::filesystem::path& path);

/// Throws InvalidInput naming `path` unless its extension (.png, .tif, .tiff, .exr) can hold depth
/// of `type`: PNG CV_16UC1, TIFF both, EXR CV_32FC1.
void check_depth_format(const std::filesystem::path& path, int type);

/// Writes a depth image in the format of the extension (check_depth_format), atomically
/// (write_file_atomically). Throws InvalidInput or IoError naming the file.
///
/// EXR goes through OpenCV's OpenEXR codec. Debian's OpenCV 4.6, built against the system OpenEXR,
/// enables it by default; builds with the bundled OpenEXR enable it only when the environment
/// variable OPENCV_IO_ENABLE_OPENEXR is set before the first EXR file is touched (the rangefill
/// program sets it when unset); a disabled codec gives an InvalidInput saying so.
void write_depth_image(const cv::Mat& depth, const std::filesystem::path& path);

/// A pinhole camera in OpenCV's convention: x right, y down, z forward; pixel (col, row) has its
/// centre at (u, v) = (col, row), so the image centre of a W×H image is ((W − 1)/2, (H − 1)/2).
struct CameraIntrinsics {
  double fx = 525, fy = 525, cx = 319.5, cy = 239.5;  // PrimeSense defaults, 640×480
};

/// The world → camera transform of a camera at `eye` looking at `target`, with `up` (world)
/// pointing up in the image (−y of the camera). Throws InvalidInput if eye = target or up is
/// parallel to the view.
Eigen::Isometry3d look_at(const Vec3& eye, const Vec3& target, const Vec3& up);

/// Renders the depth map (z along the optical axis, metres, CV_32FC1; 0 where no surface) of a mesh
/// seen by a camera with pose `world_to_camera`, by z-buffering: every triangle, either side, is
/// rasterised at the pixel centres inside it (edges shared by two triangles are drawn by both, so
/// that a closed surface shows no cracks), depth interpolated perspective-correctly (1/z is linear
/// in the image), the nearest surface winning. Triangles are clipped at z = `near`.
cv::Mat render_depth(const Mesh& mesh, const CameraIntrinsics& camera,
                     const Eigen::Isometry3d& world_to_camera, cv::Size size, double near = 1e-3);

/// Sensor-like holes for benchmarks, as a share of the valid pixels, about a third of each kind:
///  - blobs: ellipses with semi-axes of 2–10 pixels, anywhere;
///  - shadows: along 10–60 pixels of a depth edge (a jump above `discontinuity` between
///    horizontal neighbours), the far surface left of the near one, over the width a projector
///    right of the camera cannot light: disparity_scale·(1/z_near − 1/z_far) pixels, at least 1
///    (when the frame has no such edge, blobs instead);
///  - dropouts: patches of 50–600 pixels grown at random from a seed within one surface (no jump
///    above `discontinuity` between neighbours), as dark or specular materials return nothing.
struct SensorHoleOptions {
  double fraction = 0.05;  // of the valid pixels
  std::uint64_t seed = 1;
  double discontinuity = 0.05;
  double disparity_scale = 580 * 0.075;  // focal length (pixels) × baseline (m): Kinect v1
};

/// CV_8UC1, 255 at the punched pixels, all of them valid pixels of `depth` (CV_16UC1 or CV_32FC1).
/// Deterministic for a seed.
cv::Mat punch_depth_holes(cv::InputArray depth, const SensorHoleOptions& options = {});

}  // namespace rangefill
