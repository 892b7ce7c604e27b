// Fields-of-Experts models (Roth & Black): the prior behind the "foe" back-end (foe.h), its
// energy in foe_energy.h, inference in foe_map.h. A model: n filters J_i of s×s taps with weights
// α_i, and the scale of the inputs they were fitted on.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

namespace rangefill {

/// A fitted FoE model. Written and read as OpenCV FileStorage YAML (see models/README.md); Roth &
/// Black's ASCII `.foe` files are read too.
struct FoeModel {
  static constexpr int kFormatVersion = 1;
  std::string name;
  int size = 3;                  // filters are size × size, size odd
  std::vector<cv::Mat> filters;  // CV_64F correlation kernels, one per expert
  std::vector<double> alphas;    // α_i > 0
  double input_scale = 1;        // the model sees input_scale · x / divisor, where the divisor is
  bool known_rms = false;        // the RMS of the known pixels when set, else 1
  std::string normalisation;     // what x is expected to be
  std::string training;          // what data and loss fitted it, and the command

  int count() const { return static_cast<int>(filters.size()); }
};

/// Parses a model from YAML text or from Roth & Black's `.foe` format (told apart by content);
/// `name` names it in messages. Throws InvalidInput on malformed text.
FoeModel parse_foe_model(std::string_view text, const std::string& name);

/// The YAML text of a model (parse_foe_model reads it back exactly: numbers in shortest round-trip
/// form).
std::string serialize_foe_model(const FoeModel& model);

/// A model shipped with the library, by name: "depth" (fitted on depth patches by
/// `rangefill train-foe`), "roth-black" (Roth & Black's 5×5 natural-image filters, scaled to
/// inputs in [0, 1]); or a model file's path. Throws InvalidInput otherwise.
FoeModel load_foe_model(const std::string& name_or_path);

/// The names load_foe_model knows without a path.
std::vector<std::string> shipped_foe_models();

/// The divisor of the model's inputs for an image (any type) and its mask (CV_8U, 255 = unknown):
/// the RMS of the known pixels when model.known_rms (1 if they are all 0), else 1.
double foe_input_divisor(const FoeModel& model, const cv::Mat& image, const cv::Mat& mask);

}  // namespace rangefill
