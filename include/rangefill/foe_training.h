// Fitting a Fields-of-Experts model to depth by loss-specific training (Samuel & Tappen 2009; Chen,
// Pock, Ranftl & Bischof 2013): the filters and weights are chosen so that a few steps of inference
// restore the masked pixels of training patches as well as possible.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "rangefill/foe.h"
#include "rangefill/patches.h"

namespace rangefill {

/// The objective: the mean over samples (each divided by the RMS of its known pixels, as the model
/// will divide its inputs) of ½‖M ⊙ (x_T − truth)‖² / |M|, where x_T comes from T
/// gradient steps x ← x − η M ⊙ ∇E(x) started at the harmonic fill of the sample. Its parameters θ:
/// the count × (size² − 1) coefficients of the filters on the 2-D DCT basis without its constant
/// term (so every filter has zero mean; in units that make θ of order 1), then log α_i (count),
/// then log η. The gradient is exact:
/// a reverse pass through the T steps (Hessian-vector products of E, no finite differences).
class FoeObjective {
 public:
  FoeObjective(std::vector<HoleSample> samples, int size, int count, int steps, int threads);

  int parameter_count() const;
  /// The objective at θ; with `gradient`, also ∂/∂θ. Deterministic at any thread count.
  double evaluate(const std::vector<double>& theta, std::vector<double>* gradient) const;
  /// θ of the first `count` DCT filters (lowest frequencies first), all scaled so that the first
  /// one's responses on the samples have unit spread; α = 1; η = 1 / Σ α_i ‖J_i‖₁², a stable step.
  std::vector<double> initial_parameters() const;
  FoeModel model(const std::vector<double>& theta) const;
  double step(const std::vector<double>& theta) const;
  /// x_T for a sample, in the sample's units: the unrolled inference the objective scores.
  cv::Mat unrolled(const std::vector<double>& theta, const HoleSample& sample) const;

  int size() const { return size_; }
  int count() const { return count_; }
  int steps() const { return steps_; }

 private:
  std::vector<HoleSample> samples_;
  std::vector<cv::Mat> starts_;   // harmonic fills, CV_64F
  std::vector<cv::Mat> basis_;    // size × size DCT functions without the constant one
  double coefficient_scale_ = 1;  // the unit of the filter coefficients in θ
  int size_, count_, steps_, threads_;
};

struct FoeTrainingOptions {
  int size = 3;          // filters are size × size
  int count = 8;         // at most size² − 1
  int steps = 20;        // inference steps unrolled
  int iterations = 100;  // L-BFGS iterations over θ
  int threads = 2;
  /// Called after each iteration with its number, the training objective and the seconds so far.
  std::function<void(int, double, double)> progress;
};

struct FoeTraining {
  FoeModel model;
  double step = 0;  // η of the unrolled inference
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
