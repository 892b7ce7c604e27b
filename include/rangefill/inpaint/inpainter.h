// Inpainting back-ends: restore the masked pixels of a float image from the others. They know
// nothing of meshes, which is what lets the same back-ends serve mesh repair and depth maps.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

namespace rangefill {

struct InpainterOptions {
  double radius = 5;            // neighbourhood radius in pixels (telea, ns)
  std::string model = "depth";  // foe: a shipped model's name or a model file
  double mls_alpha =
      1.0 / 64;         // mls: α of eq. 6 (Wang & Oliveira), per squared pixel (docs/backends.md)
  double mls_ring = 3;  // mls: known pixels within this many pixels of a hole are fitted
  /// foe: what inference starts from, "harmonic" (its own Laplace fill) or another back-end's name
  /// (not foe): E is not convex, and the MAP found is the local minimum near the start.
  std::string foe_start = "harmonic";
  double foe_tolerance = 1e-6;  // foe: stop when a step lowers E by less than this share of E
  int foe_iterations = 100;     // foe: or after this many steps
};

/// A back-end. inpaint(depth, mask, out): `depth` is CV_32FC1; `mask` is CV_8UC1 of the same size,
/// non-zero at the pixels to restore; every other pixel of `depth` is taken as valid data. `out`
/// receives a CV_32FC1 image equal to `depth` outside the mask. Implementations are stateless once
/// made and may be called from several threads at once.
class Inpainter {
 public:
  virtual ~Inpainter() = default;
  virtual std::string name() const = 0;
  virtual void inpaint(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out) const = 0;
};

/// The back-ends by name ("telea", "ns", ...), or by "foe:MODEL" to choose the FoE model (a shipped
/// model's name or a model file; overrides options.model). Throws InvalidInput for an unknown
/// name, listing the known ones.
std::unique_ptr<Inpainter> make_inpainter(std::string_view name,
                                          const InpainterOptions& options = {});

/// The names make_inpainter accepts, in a stable order.
std::vector<std::string> inpainter_names();

/// Checks the inpaint() preconditions above; throws InvalidInput naming `who` otherwise.
void check_inpaint_arguments(cv::InputArray depth, cv::InputArray mask, const std::string& who);

/// How a back-end's inpaint() starts: checks the arguments (check_inpaint_arguments), sets `out`
/// to a copy of `depth` and returns the number of masked pixels. When every pixel is masked there
/// is nothing to go by: `out` is then set to 0.
int start_inpainting(cv::InputArray depth, cv::InputArray mask, cv::OutputArray out,
                     const std::string& who);

}  // namespace rangefill
