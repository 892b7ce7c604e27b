#include "rangefill/foe_training.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include <ceres/ceres.h>
#include <opencv2/imgproc.hpp>

#include "../filters/harmonic.h"
#include "rangefill/errors.h"

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

// The loss of one sample and, when `gradient` is given, its derivatives with respect to the taps
// (count × size², row-major), α (count) and η (1), added to `gradient`.
double sample_loss(const FoeModel& model, double step, const HoleSample& sample,
                   const cv::Mat& start, int steps, std::vector<double>* gradient) {
  const int size = model.size, r = size / 2, count = model.count();
  const cv::Rect valid(r, r, start.cols - 2 * r, start.rows - 2 * r);
  cv::Mat mask;
  sample.mask.convertTo(mask, CV_64F, 1.0 / 255);
  const double masked = std::max(1, cv::countNonZero(sample.mask));

  std::vector<cv::Mat> states{start.clone()};
  for (int t = 0; t < steps; ++t) {
    cv::Mat g;
    foe_energy(model, states.back(), &g);
    states.push_back(states.back() - step * mask.mul(g));
  }
  const cv::Mat difference = mask.mul(states.back() - sample.truth);
  const double loss = 0.5 * dot(difference, difference) / masked;
  if (!gradient) return loss;

  const int taps = size * size;
  cv::Mat lambda = difference / masked;  // ∂loss/∂x_T
  for (int t = steps - 1; t >= 0; --t) {
    const cv::Mat& x = states[t];
    const cv::Mat v = mask.mul(lambda);
    cv::Mat g = cv::Mat::zeros(x.size(), CV_64F), hessian_v = cv::Mat::zeros(x.size(), CV_64F);
    for (int i = 0; i < count; ++i) {
      const cv::Mat& kernel = model.filters[i];
      const double alpha = model.alphas[i];
      const cv::Mat y = foe_response(x, kernel);
      const cv::Mat u = foe_response(v, kernel);
      cv::Mat phi(x.size(), CV_64F), dphi(x.size(), CV_64F);
      for (int row = 0; row < x.rows; ++row) {
        for (int col = 0; col < x.cols; ++col) {
          const double yy = y.at<double>(row, col), half = 0.5 * yy * yy;
          phi.at<double>(row, col) = yy / (1 + half);
          dphi.at<double>(row, col) = (1 - half) / ((1 + half) * (1 + half));
        }
      }
      const cv::Mat influence = alpha * phi;  // zero outside `valid`, as y is
      const cv::Mat w = alpha * dphi.mul(u);
      g += foe_adjoint(influence, kernel);
      hessian_v += foe_adjoint(w, kernel);
      (*gradient)[taps * count + i] += -step * dot(u, phi);  // ∂/∂α_i
      for (int k = 0; k < taps; ++k) {
        const cv::Point offset(k % size - r, k / size - r);
        (*gradient)[taps * i + k] +=
            -step * (shifted_dot(influence, v, valid, offset) + shifted_dot(w, x, valid, offset));
      }
    }
    (*gradient)[(taps + 1) * count] += -dot(v, g);  // ∂/∂η
    lambda -= step * hessian_v;
  }
  return loss;
}

}  // namespace

FoeObjective::FoeObjective(std::vector<HoleSample> samples, int size, int count, int steps,
                           int threads)
    : samples_(std::move(samples)),
      basis_(dct_basis(size)),
      size_(size),
      count_(count),
      steps_(steps),
      threads_(std::max(1, threads)) {
  if (size < 3 || size % 2 == 0) throw InvalidInput("foe training: filter size must be odd, >= 3");
  if (count < 1 || count > size * size - 1) {
    throw InvalidInput("foe training: filter count must be in [1, size² − 1]");
  }
  // The model divides its inputs by the RMS of the known pixels (FoeModel::known_rms): so do the
  // samples, and the loss is measured in those units.
  FoeModel normalising;
  normalising.known_rms = true;
  for (HoleSample& sample : samples_) {
    // A new buffer: `samples` shares its pixels with the caller's, and assigning a MatExpr to
    // sample.truth would write them in place.
    cv::Mat truth;
    sample.truth.convertTo(truth, CV_64F,
                           1.0 / foe_input_divisor(normalising, sample.truth, sample.mask));
    sample.truth = truth;
    cv::Mat truth32, start32, start;
    sample.truth.convertTo(truth32, CV_32F);
    HarmonicInpainter().inpaint(truth32, sample.mask, start32);
    start32.convertTo(start, CV_64F);
    starts_.push_back(start);
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
}

int FoeObjective::parameter_count() const {
  return count_ * static_cast<int>(basis_.size()) + count_ + 1;
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
  model.known_rms = true;
  return model;
}

double FoeObjective::step(const std::vector<double>& theta) const {
  return std::exp(theta.back());
}

std::vector<double> FoeObjective::initial_parameters() const {
  const int functions = static_cast<int>(basis_.size());
  std::vector<double> theta(parameter_count(), 0.0);
  double lipschitz = 0;  // ‖H‖ ≤ Σ α_i ‖J_i‖₁² since |ψ'| ≤ 1
  for (int i = 0; i < count_; ++i) {
    theta[i * functions + i] = 1;
    lipschitz += std::pow(cv::norm(basis_[i] * coefficient_scale_, cv::NORM_L1), 2);
  }
  theta.back() = -std::log(std::max(lipschitz, 1e-300));  // η = 1 / L
  return theta;
}

double FoeObjective::evaluate(const std::vector<double>& theta,
                              std::vector<double>* gradient) const {
  const FoeModel foe = model(theta);
  const double eta = step(theta);
  const int taps = size_ * size_;
  const int raw = taps * count_ + count_ + 1;  // taps, α, η
  // One slot per sample, summed in sample order: the same at any thread count.
  std::vector<double> losses(samples_.size());
  std::vector<std::vector<double>> raws(gradient ? samples_.size() : 0, std::vector<double>(raw));
  std::vector<std::thread> workers;
  for (int t = 0; t < threads_; ++t) {
    workers.emplace_back([&, t] {
      for (size_t s = t; s < samples_.size(); s += threads_) {
        losses[s] =
            sample_loss(foe, eta, samples_[s], starts_[s], steps_, gradient ? &raws[s] : nullptr);
      }
    });
  }
  for (std::thread& worker : workers) worker.join();
  const double n = std::max<size_t>(1, samples_.size());
  double loss = 0;
  for (double l : losses) loss += l / n;
  if (!gradient) return loss;

  std::vector<double> total(raw, 0.0);
  for (const std::vector<double>& r : raws) {
    for (int k = 0; k < raw; ++k) total[k] += r[k] / n;
  }
  // Chain rule to θ: taps = scale · Σ_j θ_ij B_j, α = exp(a), η = exp(log η).
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
  gradient->back() = total.back() * eta;
  return loss;
}

cv::Mat FoeObjective::unrolled(const std::vector<double>& theta, const HoleSample& sample) const {
  const FoeModel foe = model(theta);
  cv::Mat truth32, start32, x, mask;
  const cv::Mat truth = sample.truth / foe_input_divisor(foe, sample.truth, sample.mask);
  truth.convertTo(truth32, CV_32F);
  HarmonicInpainter().inpaint(truth32, sample.mask, start32);
  start32.convertTo(x, CV_64F);
  sample.mask.convertTo(mask, CV_64F, 1.0 / 255);
  for (int t = 0; t < steps_; ++t) {
    cv::Mat g;
    foe_energy(foe, x, &g);
    x -= step(theta) * mask.mul(g);
  }
  return x * foe_input_divisor(foe, sample.truth, sample.mask);
}

namespace {

class CeresObjective : public ceres::FirstOrderFunction {
 public:
  explicit CeresObjective(const FoeObjective& objective) : objective_(objective) {}
  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    const std::vector<double> theta(parameters, parameters + NumParameters());
    std::vector<double> g;
    *cost = objective_.evaluate(theta, gradient ? &g : nullptr);
    if (gradient) std::copy(g.begin(), g.end(), gradient);
    return std::isfinite(*cost);
  }
  int NumParameters() const override { return objective_.parameter_count(); }

 private:
  const FoeObjective& objective_;
};

class Progress : public ceres::IterationCallback {
 public:
  Progress(const std::function<void(int, double, double)>& report) : report_(report) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    if (report_) report_(summary.iteration, summary.cost, summary.cumulative_time_in_seconds);
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const std::function<void(int, double, double)>& report_;
};

}  // namespace

FoeTraining train_foe(const std::vector<HoleSample>& training,
                      const std::vector<HoleSample>& validation,
                      const FoeTrainingOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const FoeObjective objective(training, options.size, options.count, options.steps,
                               options.threads);
  const FoeObjective held_out(validation, options.size, options.count, options.steps,
                              options.threads);
  std::vector<double> theta = objective.initial_parameters();
  FoeTraining result;
  result.training_loss_start = objective.evaluate(theta, nullptr);
  result.validation_loss_start = held_out.evaluate(theta, nullptr);

  ceres::GradientProblemSolver::Options solver;
  solver.line_search_direction_type = ceres::LBFGS;
  solver.max_num_iterations = options.iterations;
  solver.function_tolerance = 1e-9;
  solver.parameter_tolerance = 1e-12;
  solver.logging_type = ceres::SILENT;
  Progress progress(options.progress);
  solver.callbacks.push_back(&progress);
  ceres::GradientProblemSolver::Summary summary;
  ceres::GradientProblem problem(new CeresObjective(objective));
  ceres::Solve(solver, problem, theta.data(), &summary);

  result.model = objective.model(theta);
  result.step = objective.step(theta);
  result.training_loss_end = objective.evaluate(theta, nullptr);
  result.validation_loss_end = held_out.evaluate(theta, nullptr);
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.stop = summary.message;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace rangefill
