#include "rangefill/inpaint/foe_map.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <opencv2/imgproc.hpp>

#include "inpaint/foe_terms.h"
#include "rangefill/core/errors.h"
#include "rangefill/inpaint/foe_energy.h"
#include "rangefill/inpaint/harmonic.h"

namespace rangefill {

using namespace foe_terms;

namespace {

// Keeps A definite where the filters cannot see an unknown (a mask covering the image).
double ridge_of(const FoeModel& model) {
  double ridge = 0;
  for (double alpha : model.alphas) ridge += 1e-12 * alpha * model.input_scale * model.input_scale;
  return ridge;
}

// foe_map's newton method on x. One function on purpose: the kind of matrix, whether it was made
// at x and the last gain are the state of one step rule, which reads best in one place.
cv::Mat newton_map(const FoeModel& model, cv::Mat x, const cv::Mat& mask,
                   const FoeMapOptions& options, const cv::Mat& clique_weights) {
  InferenceProblem problem(model, mask);
  const std::vector<cv::Point>& unknowns = problem.unknowns.pixels;
  const int count = model.count();
  const double ridge = ridge_of(model);
  std::vector<double> gaussian(x.total() * count, 0.0);
  for (const CliqueRun& run : problem.runs) {
    for (int col = run.begin; col < run.end; ++col) {
      const double weight = clique_weights.empty() ? 1 : clique_weights.at<double>(run.row, col);
      for (int i = 0; i < count; ++i) {
        gaussian[(static_cast<size_t>(run.row) * x.cols + col) * count + i] =
            weight * model.alphas[i];
      }
    }
  }
  // CHOLMOD's supernodal Cholesky: on the (4r + 1)²-point stencils of 5×5 filters it factorises
  // faster than Eigen's simplicial LDLᵀ.
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> solver;
  solver.cholmod().print = 0;  // a matrix that is not positive definite is an answer, not an error
  solver.compute(problem.matrices.assemble(gaussian, ridge));
  auto moved = [&](const cv::Mat& from, const Eigen::VectorXd& step, double length) {
    cv::Mat to = from.clone();
    for (size_t k = 0; k < unknowns.size(); ++k) to.at<double>(unknowns[k]) -= length * step[k];
    return to;
  };
  // The start: the harmonic fill. Its maximum principle keeps it within the known values around
  // each hole, so E is entered without the overshoot of higher-order fills at depth edges.
  if (!options.start_from_image) {
    cv::Mat image32, start32;
    x.convertTo(image32, CV_32F);
    HarmonicInpainter().inpaint(image32, mask, start32);
    for (const cv::Point& p : unknowns) x.at<double>(p) = start32.at<float>(p);
  }
  // Then steps x ← x − t M⁻¹∇E, each factorisation reused while its steps gain at least twice
  // what the next one does. M starts as the Gaussian bound (ρ'' ≤ 1: it holds everywhere). When
  // progress slows, M becomes the Hessian at the current point (Newton) with the curvature of each
  // clique kept above a tenth of its half-quadratic weight, so that M stays positive definite
  // where E is not convex; near the minimum (∇E below 1e-3 of its start), the Hessian itself when
  // it is positive definite (quadratic convergence). A Newton step that would raise
  // E is halved twice, then replaced by a step with the half-quadratic bound at x (Geman & Yang),
  // which cannot raise E. The iterations end when the steps to come are predicted to gain less than
  // the tolerance, or when a matrix made at x gains less.
  enum class Matrix { bound, other } kind = Matrix::bound;
  bool fresh = false;  // M was made at x
  Evaluation current = evaluate(model, x, problem.runs, problem.unknowns, clique_weights);
  auto refresh_with_bound = [&] {
    solver.factorize(problem.matrices.assemble(current.weights.half_quadratic, ridge));
    kind = Matrix::bound;
    fresh = true;
  };
  const double start_gradient = current.gradient.lpNorm<Eigen::Infinity>();
  auto refresh = [&] {
    kind = Matrix::other;
    fresh = true;
    if (current.gradient.lpNorm<Eigen::Infinity>() < 1e-3 * start_gradient) {
      solver.factorize(problem.matrices.assemble(current.weights.curvature, ridge));
      if (solver.info() == Eigen::Success) return;
    }
    std::vector<double> damped = current.weights.curvature;
    for (size_t k = 0; k < damped.size(); ++k) {
      damped[k] = std::max(damped[k], 0.1 * current.weights.half_quadratic[k]);
    }
    solver.factorize(problem.matrices.assemble(damped, ridge));
    if (solver.info() != Eigen::Success) refresh_with_bound();
  };
  double last_gain = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    if (solver.info() != Eigen::Success ||
        current.gradient.lpNorm<Eigen::Infinity>() <= options.gradient_tolerance) {
      break;
    }
    const Eigen::VectorXd step = solver.solve(current.gradient);
    // Changes of E below `resolution` are rounding: there a step that shrinks ∇E is taken, and
    // gains tell nothing of the rate of convergence.
    const double resolution =
        64 * std::numeric_limits<double>::epsilon() * std::abs(current.energy);
    cv::Mat trial;
    Evaluation next;
    double gain = 0;
    bool taken = false;
    for (double length = 1; length >= 0.25 && !taken; length /= 2) {
      trial = moved(x, step, length);
      next = evaluate(model, trial, problem.runs, problem.unknowns, clique_weights);
      gain = current.energy - next.energy;
      taken = gain >= 0 || (gain >= -resolution && next.gradient.lpNorm<Eigen::Infinity>() <
                                                       current.gradient.lpNorm<Eigen::Infinity>());
      if (!(fresh && kind == Matrix::other)) break;  // only a fresh Newton step is shortened
    }
    if (!taken) {  // a stale matrix, or a Newton step in the wrong place
      if (fresh && kind == Matrix::bound) break;
      if (fresh) {
        refresh_with_bound();
      } else {
        refresh();
      }
      continue;
    }
    // Below the resolution of E, progress is what ∇E loses.
    const bool gradient_halved =
        next.gradient.lpNorm<Eigen::Infinity>() < 0.5 * current.gradient.lpNorm<Eigen::Infinity>();
    x = trial;
    current = std::move(next);
    // Converging linearly at rate ρ = gain / last gain, the steps to come gain gain·ρ / (1 − ρ).
    const double tolerance = options.function_tolerance * std::abs(current.energy);
    const bool have_rate = std::isfinite(last_gain) && gain > resolution;
    const double rate = have_rate ? gain / last_gain : 0;
    if (have_rate && rate < 0.5 && gain * rate / (1 - rate) <= tolerance) break;
    const bool small = gain <= tolerance && !(gain <= resolution && gradient_halved);
    if (small && fresh) break;
    if (kind == Matrix::bound && fresh) kind = Matrix::other;  // not a bound at the new x
    fresh = false;
    if (small || rate > 0.5) refresh();
    last_gain = gain;
  }
  return x;
}

// The preconditioner of foe_map's lbfgs method: H₀ = γ (L + t·L²)⁻¹, L the 5-point Laplacian over
// the unknowns. t and γ follow the Gaussian field A = Σ_i α_i J_iᵀ J_i through the symbols on a
// grid of frequencies ω ∈ (0, π]²: A(ω) = Σ_i α_i |Ĵ_i(ω)|² and λ(ω) = 4 − 2 cos ω_x − 2 cos ω_y.
// t minimises the spread max/min of A / (λ + tλ²) (the condition number of the preconditioned
// field away from the hole's border), γ is the reciprocal of the geometric mean of its extremes.
struct LaplacianPolynomial {
  double t = 0, gamma = 1;
};

LaplacianPolynomial fit_laplacian_polynomial(const FoeModel& model) {
  constexpr int kSteps = 16;
  const int size = model.size;
  // phase[a][x] = exp(−i ω_a x), ω_a = π a / kSteps.
  std::vector<std::vector<std::complex<double>>> phase(kSteps + 1);
  for (int a = 1; a <= kSteps; ++a) {
    for (int x = 0; x < size; ++x) phase[a].push_back(std::polar(1.0, -M_PI * a * x / kSteps));
  }
  // Ĵ_i(ω_a, ω_b) = Σ_y phase[b][y] · rows[y][a], rows[y][a] = Σ_x J_i(y, x) · phase[a][x].
  std::vector<double> symbol(static_cast<size_t>(kSteps) * kSteps, 0.0), laplacian;
  std::vector<std::complex<double>> rows(static_cast<size_t>(size) * (kSteps + 1));
  for (int i = 0; i < model.count(); ++i) {
    for (int y = 0; y < size; ++y) {
      for (int a = 1; a <= kSteps; ++a) {
        std::complex<double> sum = 0;
        for (int x = 0; x < size; ++x) sum += model.filters[i].at<double>(y, x) * phase[a][x];
        rows[y * (kSteps + 1) + a] = sum;
      }
    }
    for (int a = 1; a <= kSteps; ++a) {
      for (int b = 1; b <= kSteps; ++b) {
        std::complex<double> response = 0;
        for (int y = 0; y < size; ++y) response += rows[y * (kSteps + 1) + a] * phase[b][y];
        symbol[(a - 1) * kSteps + b - 1] +=
            model.alphas[i] * std::norm(response * model.input_scale);
      }
    }
  }
  for (int a = 1; a <= kSteps; ++a) {
    for (int b = 1; b <= kSteps; ++b) {
      laplacian.push_back(4 - 2 * std::cos(M_PI * a / kSteps) - 2 * std::cos(M_PI * b / kSteps));
    }
  }
  auto extremes = [&](double t) {
    double low = std::numeric_limits<double>::infinity(), high = 0;
    for (size_t k = 0; k < symbol.size(); ++k) {
      const double ratio = symbol[k] / (laplacian[k] + t * laplacian[k] * laplacian[k]);
      low = std::min(low, ratio);
      high = std::max(high, ratio);
    }
    return std::make_pair(low, high);
  };
  LaplacianPolynomial best;
  double best_spread = std::numeric_limits<double>::infinity();
  for (double t = 1e-3; t < 1e3; t *= 1.1) {
    const auto [low, high] = extremes(t);
    if (low > 0 && high / low < best_spread) {
      best_spread = high / low;
      best = {t, 1 / std::sqrt(low * high)};
    }
  }
  return best;
}

// E and ∇E over the unknowns for the lbfgs method: the responses of every filter at the cliques
// that see an unknown as blocked matrix products (taps × cliques patches) in single precision,
// twice the SIMD width of double on the baseline x86-64 target; E and ∇E summed in double, in one
// order at any thread count. Each clique's terms times its `clique_weights` (empty: 1).
class BlockedEnergy {
 public:
  BlockedEnergy(const FoeModel& model, const cv::Mat& mask, const Unknowns& unknowns,
                const cv::Mat& clique_weights)
      : unknowns_(unknowns), alphas_(model.alphas) {
    const int r = model.size / 2, taps = model.size * model.size;
    for (const CliqueRun& run : cliques_touching(mask, r)) {
      for (int col = run.begin; col < run.end; ++col) {
        centres_.push_back(run.row * mask.cols + col);
        if (!clique_weights.empty())
          clique_weights_.push_back(clique_weights.at<double>(run.row, col));
      }
    }
    filters_.resize(model.count(), taps);
    for (int i = 0; i < model.count(); ++i) {
      for (int t = 0; t < taps; ++t) {
        filters_(i, t) = static_cast<float>(
            model.filters[i].at<double>(t / model.size, t % model.size) * model.input_scale);
      }
    }
    for (int dy = -r; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) offsets_.push_back(dy * mask.cols + dx);
    }
  }

  // E(x) over the cliques, and ∂E/∂u at the unknowns into `gradient`.
  double operator()(const cv::Mat& x, Eigen::VectorXd& gradient) {
    constexpr int kBlock = 256;
    const int taps = static_cast<int>(offsets_.size()), count = static_cast<int>(alphas_.size());
    const int cliques = static_cast<int>(centres_.size());
    patches_.resize(taps, kBlock);
    responses_.resize(count, kBlock);
    back_.resize(taps, kBlock);
    full_gradient_ = cv::Mat::zeros(x.size(), CV_64F);
    const double* in = x.ptr<double>();
    double* out = full_gradient_.ptr<double>();
    double energy = 0;
    std::vector<double> product(count);
    for (int first = 0; first < cliques; first += kBlock) {
      const int block = std::min(kBlock, cliques - first);
      for (int c = 0; c < block; ++c) {
        const double* centre = in + centres_[first + c];
        float* patch = patches_.col(c).data();
        for (int t = 0; t < taps; ++t) patch[t] = static_cast<float>(centre[offsets_[t]]);
      }
      responses_.leftCols(block).noalias() = filters_ * patches_.leftCols(block);
      // Σ α_i log(1 + y²/2) as α_i log of products of four factors: as y is a float, each factor
      // is below 6e76 and a product of four stays finite; a quarter of the logarithms. Weighted
      // cliques each take their own logarithms.
      const bool weighted = !clique_weights_.empty();
      for (int c = 0; c < block; ++c) {
        float* y = responses_.col(c).data();
        const double weight = weighted ? clique_weights_[first + c] : 1;
        if (weighted || c % 4 == 0) std::fill(product.begin(), product.end(), 1.0);
        for (int i = 0; i < count; ++i) {
          const double response = y[i], factor = 1 + 0.5 * response * response;
          product[i] *= factor;
          y[i] = static_cast<float>(weight * alphas_[i] * response / factor);  // ψ_i(y)
        }
        if (weighted || c % 4 == 3 || c == block - 1) {
          for (int i = 0; i < count; ++i) energy += weight * alphas_[i] * std::log(product[i]);
        }
      }
      back_.leftCols(block).noalias() = filters_.transpose() * responses_.leftCols(block);
      for (int c = 0; c < block; ++c) {
        double* centre = out + centres_[first + c];
        const float* column = back_.col(c).data();
        for (int t = 0; t < taps; ++t) centre[offsets_[t]] += column[t];
      }
    }
    gradient.resize(unknowns_.pixels.size());
    for (size_t k = 0; k < unknowns_.pixels.size(); ++k) {
      gradient[k] = full_gradient_.at<double>(unknowns_.pixels[k]);
    }
    return energy;
  }

 private:
  const Unknowns& unknowns_;
  std::vector<double> alphas_;
  std::vector<int> centres_;            // of the cliques, as offsets into the image's data
  std::vector<double> clique_weights_;  // of the cliques, or empty
  std::vector<int> offsets_;            // of the taps from the centre, row-major over the filter
  Eigen::MatrixXf filters_;             // count × taps, scaled by the model's input scale
  Eigen::MatrixXf patches_, responses_, back_;
  cv::Mat full_gradient_;
};

// p(A)·r ≈ A⁻¹r for an SPD matrix A with spectrum in [1, highest]: a fixed number of Chebyshev
// semi-iteration steps from 0 (Saad, Iterative Methods, 12.1), enough for a relative error of
// 1/10 at most. p(A) is a polynomial in A, so it is symmetric, and positive as |1 − λp(λ)| < 1 on
// the spectrum: an SPD operator, cheaper than a factorisation when A is well-conditioned (I + tL,
// of condition 1 + 8t).
class ChebyshevInverse {
 public:
  ChebyshevInverse(const Eigen::SparseMatrix<double>& matrix, double highest)
      : matrix_(matrix), centre_((1 + highest) / 2), half_width_((highest - 1) / 2) {
    const double ratio = (std::sqrt(highest) - 1) / (std::sqrt(highest) + 1);  // per step
    steps_ = ratio > 0 ? static_cast<int>(std::ceil(std::log(20.0) / -std::log(ratio))) : 1;
  }

  Eigen::VectorXd operator()(const Eigen::VectorXd& r) const {
    if (!(half_width_ > 0)) return r / centre_;  // A = I
    const double sigma = centre_ / half_width_;
    double rho = 1 / sigma;
    Eigen::VectorXd y = Eigen::VectorXd::Zero(r.size()), residual = r, step = r / centre_;
    for (int k = 1;; ++k) {
      y += step;
      if (k == steps_) return y;
      residual -= matrix_ * step;
      const double next = 1 / (2 * sigma - rho);
      step = next * rho * step + (2 * next / half_width_) * residual;
      rho = next;
    }
  }

 private:
  const Eigen::SparseMatrix<double>& matrix_;
  double centre_, half_width_;
  int steps_ = 1;
};

// foe_map's lbfgs method on x (some pixel known). Ceres' GradientProblem
// solver has no preconditioner hook (a change of variables would need a triangular factor of
// L + tL², a 13-point matrix that alone costs most of the time budget), hence the loop here, in
// one function like newton_map: the two-loop recursion and the line search share its history.
cv::Mat lbfgs_map(const FoeModel& model, const LaplacianPolynomial& polynomial, cv::Mat x,
                  const cv::Mat& mask, const FoeMapOptions& options,
                  const cv::Mat& clique_weights) {
  constexpr int kMemory = 10;       // correction pairs kept
  constexpr double kArmijo = 1e-4;  // sufficient decrease
  const Unknowns unknowns(mask);
  const int n = static_cast<int>(unknowns.pixels.size());
  const LaplaceSystem laplace = laplace_system(x, mask);
  const LaplaceFactor laplacian(laplace.matrix, mask);
  Eigen::SparseMatrix<double> shifted = polynomial.t * laplace.matrix;
  for (int k = 0; k < n; ++k) shifted.coeffRef(k, k) += 1;
  const ChebyshevInverse one_plus_t_laplacian(shifted, 1 + 8 * polynomial.t);
  // (L + tL²)⁻¹ = (I + tL)⁻¹ L⁻¹: the two commute, and so does the polynomial in I + tL that
  // stands for its inverse.
  auto precondition = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    return one_plus_t_laplacian(laplacian.solve(v));
  };
  auto place = [&](const Eigen::VectorXd& u) {
    for (int k = 0; k < n; ++k) x.at<double>(unknowns.pixels[k]) = u[k];
  };

  BlockedEnergy energy_of(model, mask, unknowns, clique_weights);
  Eigen::VectorXd u(n), gradient;
  if (options.start_from_image) {
    for (int k = 0; k < n; ++k) u[k] = x.at<double>(unknowns.pixels[k]);
  } else {
    u = laplacian.solve(laplace.rhs);  // the harmonic start
    place(u);
  }
  double energy = energy_of(x, gradient);
  std::vector<Eigen::VectorXd> steps, changes;  // s_k, y_k of the two-loop recursion
  std::vector<double> rhos;
  for (int iteration = 0; iteration < options.max_iterations &&
                          gradient.lpNorm<Eigen::Infinity>() > options.gradient_tolerance;
       ++iteration) {
    Eigen::VectorXd direction = gradient;
    std::vector<double> weights(steps.size());
    for (int k = static_cast<int>(steps.size()) - 1; k >= 0; --k) {
      weights[k] = rhos[k] * steps[k].dot(direction);
      direction -= weights[k] * changes[k];
    }
    direction = polynomial.gamma * precondition(direction);
    for (size_t k = 0; k < steps.size(); ++k) {
      direction += steps[k] * (weights[k] - rhos[k] * changes[k].dot(direction));
    }
    direction = -direction;
    double slope = gradient.dot(direction);
    if (!(slope < 0)) {  // the memory misleads: start it again
      steps.clear();
      changes.clear();
      rhos.clear();
      direction = -polynomial.gamma * precondition(gradient);
      slope = gradient.dot(direction);
    }
    Eigen::VectorXd trial, trial_gradient;
    double trial_energy = energy;
    bool accepted = false;
    for (double length = 1; length > 1e-6 && !accepted; length /= 2) {
      trial = u + length * direction;
      place(trial);
      trial_energy = energy_of(x, trial_gradient);
      accepted = trial_energy <= energy + kArmijo * length * slope;
    }
    if (!accepted) {
      place(u);
      break;
    }
    Eigen::VectorXd step = trial - u, change = trial_gradient - gradient;
    const double curvature = step.dot(change);
    if (curvature > 1e-12 * step.norm() * change.norm()) {
      if (static_cast<int>(steps.size()) == kMemory) {
        steps.erase(steps.begin());
        changes.erase(changes.begin());
        rhos.erase(rhos.begin());
      }
      steps.push_back(std::move(step));
      changes.push_back(std::move(change));
      rhos.push_back(1 / curvature);
    }
    const double gain = energy - trial_energy;
    u = std::move(trial);
    gradient = std::move(trial_gradient);
    energy = trial_energy;
    if (gain <= options.function_tolerance * std::abs(energy)) break;
  }
  return x;
}

// The lbfgs method on each group of unknowns separately, each on its bounding box grown by 2r:
// unknowns more than 2r apart (r the filters' radius) share no clique, so the groups' MAPs are
// independent, and smaller problems factorise and converge faster (a depth map's many holes).
cv::Mat lbfgs_map_by_groups(const FoeModel& model, cv::Mat x, const cv::Mat& mask,
                            const FoeMapOptions& options, const cv::Mat& clique_weights) {
  const int reach = 2 * (model.size / 2);
  const LaplacianPolynomial polynomial = fit_laplacian_polynomial(model);
  cv::Mat grown, labels, stats, centroids;
  cv::dilate(mask, grown, cv::Mat::ones(reach + 1, reach + 1, CV_8U));
  const int groups = cv::connectedComponentsWithStats(grown, labels, stats, centroids, 8, CV_32S);
  for (int group = 1; group < groups; ++group) {
    // The group's unknowns lie within its grown component's box; only there is it searched.
    const cv::Rect component(
        stats.at<int>(group, cv::CC_STAT_LEFT), stats.at<int>(group, cv::CC_STAT_TOP),
        stats.at<int>(group, cv::CC_STAT_WIDTH), stats.at<int>(group, cv::CC_STAT_HEIGHT));
    cv::Rect box = cv::boundingRect((labels(component) == group) & mask(component));
    box = cv::Rect(component.x + box.x - reach, component.y + box.y - reach, box.width + 2 * reach,
                   box.height + 2 * reach) &
          cv::Rect(0, 0, x.cols, x.rows);
    const cv::Mat unknowns = (labels(box) == group) & mask(box);
    const cv::Mat part = lbfgs_map(model, polynomial, x(box).clone(), unknowns, options,
                                   clique_weights.empty() ? cv::Mat() : clique_weights(box));
    part.copyTo(x(box), unknowns);
  }
  return x;
}

}  // namespace

cv::Mat foe_map(const FoeModel& model, const cv::Mat& image, const cv::Mat& mask,
                const FoeMapOptions& options, const cv::Mat& clique_weights) {
  check_energy_argument(image);
  CV_Assert(mask.type() == CV_8UC1 && mask.size() == image.size());
  check_clique_weights(clique_weights, image);
  cv::Mat x = image.clone();
  const int unknowns = cv::countNonZero(mask);
  if (unknowns == 0) return x;
  if (unknowns == static_cast<int>(mask.total())) return x.setTo(0);
  if (options.start_from_image) {
    if (!cv::checkRange(x)) throw InvalidInput("foe_map: the start is not finite");
  } else {
    x.setTo(0, mask);
  }
  return options.method == FoeMapMethod::newton
             ? newton_map(model, x, mask, options, clique_weights)
             : lbfgs_map_by_groups(model, x, mask, options, clique_weights);
}

}  // namespace rangefill
