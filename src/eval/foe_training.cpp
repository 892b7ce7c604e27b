#include "rangefill/eval/foe_training.h"

#include "rangefill/inpaint/foe_energy.h"
#include "rangefill/inpaint/foe_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <Eigen/SparseCholesky>
#include <opencv2/imgproc.hpp>

#include "core/module_loader.h"
#include "eval/foe_lbfgs.h"
#include "rangefill/core/errors.h"
#include "rangefill/core/parallel.h"

namespace rangefill {

namespace {

// The 2-D DCT-II basis of size × size without its constant function, lowest frequencies first.
std::vector<cv::Mat> dct_basis(int size) {
  std::vector<std::pair<std::pair<int, int>, cv::Mat>> functions;
  for (int p = 0; p < size; ++p) {
    for (int q = 0; q < size; ++q) {
      if (p == 0 && q == 0) continue;
      cv::Mat function(size, size, CV_64F);
      const double cp = std::sqrt((p == 0 ? 1.0 : 2.0) / size);
      const double cq = std::sqrt((q == 0 ? 1.0 : 2.0) / size);
      for (int m = 0; m < size; ++m) {
        for (int n = 0; n < size; ++n) {
          function.at<double>(m, n) = cp * cq * std::cos(M_PI * (2 * m + 1) * p / (2 * size)) *
                                      std::cos(M_PI * (2 * n + 1) * q / (2 * size));
        }
      }
      functions.push_back({{p + q, p}, function});
    }
  }
  std::stable_sort(functions.begin(), functions.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<cv::Mat> basis;
  for (auto& entry : functions) basis.push_back(entry.second);
  return basis;
}

// Σ a·b over two CV_64F images of one size, row by row: cv::Mat::dot may split the sum
// differently when called from several threads, and the objective must not depend on them.
double dot(const cv::Mat& a, const cv::Mat& b) {
  double sum = 0;
  for (int row = 0; row < a.rows; ++row) {
    const double* x = a.ptr<double>(row);
    const double* y = b.ptr<double>(row);
    for (int col = 0; col < a.cols; ++col) sum += x[col] * y[col];
  }
  return sum;
}

// Σ_{c in valid} a[c] · b[c + offset].
double shifted_dot(const cv::Mat& a, const cv::Mat& b, const cv::Rect& valid, cv::Point offset) {
  return dot(a(valid), b(valid + offset));
}

// The MAP estimate the objective scores: iterations until ∇_u E vanishes, as the implicit gradient
// assumes (foe_map ends with Newton steps, which get there); a tolerance on E would stop them
// where E no longer changes but ∇_u E has not vanished yet.
constexpr FoeMapOptions kTrainingMap{200, 0, 1e-11, FoeMapMethod::newton};

// The loss of one sample and, when `gradient` is given, its derivatives with respect to the taps
// (count × size², row-major) and α (count), added to `gradient`. At the MAP x*, ∇_u E(x*, θ) = 0,
// so dx*/dθ = −H⁻¹ ∂(∇_u E)/∂θ and dL/dθ = −λᵀ ∂(∇_u E)/∂θ with H λ = ∂L/∂u (Samuel & Tappen,
// "Learning optimized MAP estimates in continuously-valued MRF models", 2009).
double sample_loss(const FoeModel& model, const HoleSample& sample, std::vector<double>* gradient) {
  const int size = model.size, r = size / 2, count = model.count();
  const cv::Rect valid(r, r, sample.truth.cols - 2 * r, sample.truth.rows - 2 * r);
  std::vector<cv::Point> unknowns;
  cv::findNonZero(sample.mask, unknowns);
  const int n = static_cast<int>(unknowns.size());
  const cv::Mat x = foe_map(model, sample.truth, sample.mask, kTrainingMap);
  const double masked = std::max(1, n);
  double loss = 0;
  Eigen::VectorXd loss_gradient(n);
  for (int k = 0; k < n; ++k) {
    const double difference = x.at<double>(unknowns[k]) - sample.truth.at<double>(unknowns[k]);
    loss += 0.5 * difference * difference / masked;
    loss_gradient[k] = difference / masked;
  }
  if (!gradient || n == 0) return loss;

  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> hessian(
      foe_hessian_of_unknowns(model, x, sample.mask));
  const Eigen::VectorXd lambda = hessian.solve(loss_gradient);
  cv::Mat v = cv::Mat::zeros(x.size(), CV_64F);
  for (int k = 0; k < n; ++k) v.at<double>(unknowns[k]) = lambda[k];

  // ∂(vᵀ ∇E)/∂θ: for α_i, Σ_c u_c ψ(y_c); for tap k of J_i, Σ_c α_i (ψ(y_c) v[c+k] +
  // ψ'(y_c) u_c x[c+k]), with y = J_i ⋆ x, u = J_i ⋆ v, ψ = ρ'.
  const int taps = size * size;
  for (int i = 0; i < count; ++i) {
    const cv::Mat& kernel = model.filters[i];
    const double alpha = model.alphas[i];
    const cv::Mat y = foe_response(x, kernel), u = foe_response(v, kernel);
    cv::Mat psi(x.size(), CV_64F), curvature(x.size(), CV_64F);
    for (int row = 0; row < x.rows; ++row) {
      for (int col = 0; col < x.cols; ++col) {
        const double yy = y.at<double>(row, col), half = 0.5 * yy * yy;
        psi.at<double>(row, col) = yy / (1 + half);
        curvature.at<double>(row, col) = (1 - half) / ((1 + half) * (1 + half));
      }
    }
    const cv::Mat influence = alpha * psi;  // zero outside `valid`, as y is
    const cv::Mat w = alpha * curvature.mul(u);
    (*gradient)[taps * count + i] -= dot(u, psi);
    for (int k = 0; k < taps; ++k) {
      const cv::Point offset(k % size - r, k / size - r);
      (*gradient)[taps * i + k] -=
          shifted_dot(influence, v, valid, offset) + shifted_dot(w, x, valid, offset);
    }
  }
  return loss;
}

}  // namespace

FoeObjective::FoeObjective(std::vector<HoleSample> samples, int size, int count, int threads,
                           bool known_rms, std::optional<FoeModel> start)
    : samples_(std::move(samples)),
      basis_(dct_basis(size)),
      size_(size),
      count_(count),
      threads_(std::max(1, threads)),
      known_rms_(known_rms),
      start_(std::move(start)) {
  if (size < 3 || size % 2 == 0) throw InvalidInput("foe training: filter size must be odd, >= 3");
  if (count < 1 || count > 3 * (size * size - 1)) {
    throw InvalidInput("foe training: filter count must be in [1, 3 (size² − 1)]");
  }
  // When the model divides its inputs by the RMS of the known pixels (FoeModel::known_rms), so do
  // the samples, and the loss is measured in those units.
  FoeModel normalising;
  normalising.known_rms = known_rms;
  for (HoleSample& sample : samples_) {
    // A new buffer: `samples` shares its pixels with the caller's, and assigning a MatExpr to
    // sample.truth would write them in place.
    cv::Mat truth;
    sample.truth.convertTo(truth, CV_64F,
                           1.0 / foe_input_divisor(normalising, sample.truth, sample.mask));
    sample.truth = truth;
  }
  // θ holds the filters' coefficients in units of `coefficient_scale_`, chosen so that the
  // lowest-frequency DCT filter's responses on the samples have unit spread: then the experts'
  // heavy tails matter where the data has its largest responses, and θ is of order 1.
  const int r = size_ / 2;
  double sum = 0, pixels = 0;
  for (const HoleSample& sample : samples_) {
    const cv::Rect valid(r, r, sample.truth.cols - 2 * r, sample.truth.rows - 2 * r);
    const cv::Mat y = foe_response(sample.truth, basis_[0]);
    sum += dot(y, y);
    pixels += valid.area();
  }
  const double spread = std::sqrt(sum / std::max(1.0, pixels));
  coefficient_scale_ = spread > 0 ? 1.0 / spread : 1.0;
  if (start_) {
    // Started from a model, θ's unit is its RMS filter coefficient instead: Roth & Black's are
    // far larger than the unit above, which would make L-BFGS's first step, the gradient itself,
    // too short to be told from the small jumps of the MAP between basins.
    coefficient_scale_ = 1;
    const std::vector<double> theta = parameters_of(*start_);
    const int coefficients = count_ * static_cast<int>(basis_.size());
    double squares = 0;
    for (int k = 0; k < coefficients; ++k) squares += theta[k] * theta[k];
    const double rms = std::sqrt(squares / coefficients);
    if (rms > 0) coefficient_scale_ = rms;
  }
}

int FoeObjective::parameter_count() const {
  return count_ * static_cast<int>(basis_.size()) + count_;
}

FoeModel FoeObjective::model(const std::vector<double>& theta) const {
  FoeModel model;
  model.size = size_;
  const int functions = static_cast<int>(basis_.size());
  for (int i = 0; i < count_; ++i) {
    cv::Mat filter = cv::Mat::zeros(size_, size_, CV_64F);
    for (int j = 0; j < functions; ++j) {
      filter += theta[i * functions + j] * coefficient_scale_ * basis_[j];
    }
    model.filters.push_back(filter);
    model.alphas.push_back(std::exp(theta[functions * count_ + i]));
  }
  model.input_scale = 1;
  model.known_rms = known_rms_;
  return model;
}

std::vector<double> FoeObjective::initial_parameters() const {
  if (start_) return parameters_of(*start_);
  const int functions = static_cast<int>(basis_.size());
  std::vector<double> theta(parameter_count(), 0.0);  // α = 1
  for (int i = 0; i < count_; ++i) {
    // Beyond the basis, sums and then differences of neighbouring basis functions.
    const int round = i / functions, j = i % functions;
    theta[i * functions + j] = round == 0 ? 1 : std::sqrt(0.5);
    if (round > 0)
      theta[i * functions + (j + 1) % functions] = round == 1 ? std::sqrt(0.5) : -std::sqrt(0.5);
  }
  return theta;
}

std::vector<double> FoeObjective::parameters_of(const FoeModel& model) const {
  if (model.size != size_ || model.count() != count_ || model.known_rms != known_rms_) {
    throw InvalidInput("foe training: the initial model '" + model.name +
                       "' differs in filter size, count or normalisation");
  }
  const int functions = static_cast<int>(basis_.size());
  std::vector<double> theta(parameter_count(), 0.0);
  for (int i = 0; i < count_; ++i) {
    const cv::Mat filter = model.filters[i] * model.input_scale;  // the model sees input_scale · x
    for (int j = 0; j < functions; ++j) {
      theta[i * functions + j] = dot(filter, basis_[j]) / coefficient_scale_;  // orthonormal basis
    }
    theta[functions * count_ + i] = std::log(model.alphas[i]);
  }
  return theta;
}

double FoeObjective::evaluate(const std::vector<double>& theta,
                              std::vector<double>* gradient) const {
  const FoeModel foe = model(theta);
  const int taps = size_ * size_;
  const int raw = taps * count_ + count_;  // taps, α
  // One slot per sample, summed in sample order: the same at any thread count.
  std::vector<double> losses(samples_.size());
  std::vector<std::vector<double>> raws(gradient ? samples_.size() : 0, std::vector<double>(raw));
  parallel_for(static_cast<int>(samples_.size()), threads_, [&](int s) {
    losses[s] = sample_loss(foe, samples_[s], gradient ? &raws[s] : nullptr);
  });
  const double n = std::max<size_t>(1, samples_.size());
  double loss = 0;
  for (double l : losses) loss += l / n;
  if (!gradient) return loss;

  std::vector<double> total(raw, 0.0);
  for (const std::vector<double>& r : raws) {
    for (int k = 0; k < raw; ++k) total[k] += r[k] / n;
  }
  // Chain rule to θ: taps = scale · Σ_j θ_ij B_j, α = exp(a).
  const int functions = static_cast<int>(basis_.size());
  gradient->assign(parameter_count(), 0.0);
  for (int i = 0; i < count_; ++i) {
    for (int j = 0; j < functions; ++j) {
      double sum = 0;
      for (int k = 0; k < taps; ++k) {
        sum += total[taps * i + k] * basis_[j].at<double>(k / size_, k % size_);
      }
      (*gradient)[i * functions + j] = sum * coefficient_scale_;
    }
    (*gradient)[functions * count_ + i] = total[taps * count_ + i] * foe.alphas[i];
  }
  return loss;
}

FoeTraining train_foe(const std::vector<HoleSample>& training,
                      const std::vector<HoleSample>& validation,
                      const FoeTrainingOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const FoeObjective objective(training, options.size, options.count, options.threads,
                               options.known_rms, options.initial_model);
  const FoeObjective held_out(validation, options.size, options.count, options.threads,
                              options.known_rms, options.initial_model);
  std::vector<double> theta = objective.initial_parameters();
  // θ's unit depends on each objective's samples (without a start model), so the held-out loss is
  // taken of the model θ stands for, re-expressed in the held-out objective's units.
  const auto validation_loss = [&](const std::vector<double>& theta) {
    return held_out.evaluate(held_out.parameters_of(objective.model(theta)), nullptr);
  };
  FoeTraining result;
  result.training_loss_start = objective.evaluate(theta, nullptr);
  result.validation_loss_start = validation_loss(theta);

  static const auto lbfgs = reinterpret_cast<foe_lbfgs::Entry>(
      module_entry(foe_lbfgs::kModule, foe_lbfgs::kEntry, reinterpret_cast<const void*>(&train_foe),
                   "FoE training"));
  lbfgs(objective, options, theta, result.iterations, result.stop);

  result.model = objective.model(theta);
  result.training_loss_end = objective.evaluate(theta, nullptr);
  result.validation_loss_end = validation_loss(theta);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace rangefill
