// Fitting a Fields-of-Experts model to depth by loss-specific training (Samuel & Tappen, "Learning
// optimized MAP estimates in continuously-valued MRF models", 2009): the filters and weights are
// chosen so that the MAP estimate the "foe" back-end computes restores the masked pixels of
// training patches as well as possible.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rangefill/eval/patches.h"
#include "rangefill/inpaint/foe_model.h"

namespace rangefill {

/// The objective: the mean over samples (each divided by the RMS of its known pixels when the model
/// will divide its inputs so) of ½‖M ⊙ (x* − truth)‖² / |M|, where x* = foe_map of the sample, as
/// at repair time. Its parameters θ: the count × (size² − 1) coefficients of the filters on the 2-D
/// DCT basis without its constant term (so every filter has zero mean; in units that make θ of
/// order 1), then log α_i (count). The gradient is exact up to the MAP's convergence: implicit
/// differentiation of ∇_u E(x*) = 0, one solve with the Hessian of E over the unknowns per sample.
class FoeObjective {
 public:
  /// `known_rms`: the model divides its inputs by the RMS of their known pixels (FoeModel).
  /// `start`: the model θ starts from (initial_parameters), else the DCT basis; it must have this
  /// size, count and normalisation (else InvalidInput).
  FoeObjective(std::vector<HoleSample> samples, int size, int count, int threads,
               bool known_rms = true, std::optional<FoeModel> start = std::nullopt);

  int parameter_count() const;
  /// The objective at θ; with `gradient`, also ∂/∂θ. Deterministic at any thread count.
  double evaluate(const std::vector<double>& theta, std::vector<double>* gradient) const;
  /// θ of the first `count` DCT filters (lowest frequencies first; past the basis, normalised sums
  /// and then differences of neighbouring ones), all scaled so that the first one's responses on
  /// the samples have unit spread; α = 1.
  /// With a start model, its θ.
  std::vector<double> initial_parameters() const;
  /// θ of `model`'s filters (their constant parts dropped) and weights. Throws InvalidInput unless
  /// it has this objective's filter size, count and normalisation.
  std::vector<double> parameters_of(const FoeModel& model) const;
  FoeModel model(const std::vector<double>& theta) const;

 private:
  std::vector<HoleSample> samples_;
  std::vector<cv::Mat> basis_;    // size × size DCT functions without the constant one
  double coefficient_scale_ = 1;  // the unit of the filter coefficients in θ
  int size_, count_, threads_;
  bool known_rms_;
  std::optional<FoeModel> start_;
};

struct FoeTrainingOptions {
  int size = 3;            // filters are size × size
  int count = 8;           // at most 3 (size² − 1): the filters may be over-complete
  int iterations = 100;    // L-BFGS iterations over θ
  double max_seconds = 0;  // stop after this long (0: no limit); the result then depends on speed
  bool known_rms = true;   // inputs divided by the RMS of their known pixels (FoeModel::known_rms)
  std::optional<FoeModel> initial_model;  // start from its filters and weights, not the DCT
  int threads = 2;
  /// Called after each iteration with its number, the training objective, the seconds so far and
  /// the model of the current θ (a checkpoint).
  std::function<void(int, double, double, const FoeModel&)> progress;
};

struct FoeTraining {
  FoeModel model;
  double training_loss_start = 0, training_loss_end = 0;
  double validation_loss_start = 0, validation_loss_end = 0;
  int iterations = 0;
  double seconds = 0;
  std::string stop;  // why L-BFGS stopped (Ceres' message)
};

/// Fits θ by L-BFGS (Ceres' GradientProblemSolver) on `training`; scores `validation` at the start
/// and the end. The model's `normalisation` says what inputs it expects; `training` is left for the
/// caller to describe the data and command.
FoeTraining train_foe(const std::vector<HoleSample>& training,
                      const std::vector<HoleSample>& validation, const FoeTrainingOptions& options);

}  // namespace rangefill
