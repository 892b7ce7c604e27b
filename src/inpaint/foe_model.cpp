#include "rangefill/inpaint/foe_model.h"

#include <cmath>
#include <complex>
#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <opencv2/imgproc.hpp>

#include "inpaint/shipped_models.h"
#include "rangefill/core/errors.h"
#include "rangefill/inpaint/harmonic.h"

namespace rangefill {

namespace {

[[noreturn]] void malformed(const std::string& name, const std::string& what) {
  throw InvalidInput(name + ": " + what);
}

// Roth & Black's ASCII format: "s K", the x and y offsets of the s² taps, K alphas, K rows of s²
// coefficients. Their filters were learned on grey levels 0–255: inputs in [0, 1] are scaled up.
FoeModel parse_roth_black(std::string_view text, const std::string& name) {
  std::istringstream in{std::string(text)};
  FoeModel model;
  int count = 0;
  if (!(in >> model.size >> count) || model.size < 1 || model.size > 15 || model.size % 2 == 0 ||
      count < 1 || count > 1024) {
    malformed(name, "bad FoE header (filter size and count)");
  }
  const int taps = model.size * model.size;
  std::vector<int> xs(taps), ys(taps);
  for (int& x : xs) in >> x;
  for (int& y : ys) in >> y;
  model.alphas.resize(count);
  for (double& alpha : model.alphas) in >> alpha;
  for (int i = 0; i < count; ++i) {
    cv::Mat filter = cv::Mat::zeros(model.size, model.size, CV_64F);
    for (int k = 0; k < taps; ++k) {
      double value = 0;
      in >> value;
      if (xs[k] < 0 || xs[k] >= model.size || ys[k] < 0 || ys[k] >= model.size) {
        malformed(name, "tap offset outside the filter");
      }
      filter.at<double>(ys[k], xs[k]) = value;
    }
    // The filters were learned in a basis without the constant function, but the printed taps sum
    // to up to 1e-3 of their magnitude: remove that mean, or a constant image is not a minimiser
    // (at grey-level scale a flat 0.25 would read as responses of 0.5).
    filter -= cv::mean(filter)[0];
    model.filters.push_back(filter);
  }
  if (!in) malformed(name, "truncated FoE file");
  model.name = name;
  model.input_scale = 255;
  model.normalisation = "image values in [0, 1], seen by the filters as grey levels 0-255";
  model.training = "Roth & Black, natural images (BSDS), contrastive divergence";
  return model;
}

void check(const FoeModel& model, const std::string& name) {
  if (model.size < 1 || model.size % 2 == 0) malformed(name, "filter size must be odd");
  if (model.filters.empty() || model.filters.size() != model.alphas.size()) {
    malformed(name, "needs as many alphas as filters, at least one");
  }
  for (double alpha : model.alphas) {
    if (!(alpha > 0) || !std::isfinite(alpha)) malformed(name, "alphas must be positive");
  }
  if (!(model.input_scale > 0) || !std::isfinite(model.input_scale)) {
    malformed(name, "input_scale must be positive");
  }
}

}  // namespace

FoeModel parse_foe_model(std::string_view text, const std::string& name) {
  if (text.substr(0, 5) != "%YAML") {
    FoeModel model = parse_roth_black(text, name);
    check(model, name);
    return model;
  }
  FoeModel model;
  try {
    cv::FileStorage storage(std::string(text), cv::FileStorage::READ | cv::FileStorage::MEMORY);
    if ((int)storage["format_version"] != FoeModel::kFormatVersion) {
      malformed(name, "unsupported FoE model format_version");
    }
    storage["name"] >> model.name;
    model.size = (int)storage["filter_size"];
    const int count = (int)storage["filter_count"];
    storage["input_scale"] >> model.input_scale;
    model.known_rms = (int)storage["known_rms"] != 0;
    storage["normalisation"] >> model.normalisation;
    storage["training"] >> model.training;
    cv::Mat alphas, filters;
    storage["alphas"] >> alphas;
    storage["filters"] >> filters;
    if (alphas.total() != static_cast<size_t>(count) || filters.rows != count ||
        filters.cols != model.size * model.size || count < 1) {
      malformed(name, "alphas and filters do not match filter_size and filter_count");
    }
    alphas.convertTo(alphas, CV_64F);
    filters.convertTo(filters, CV_64F);
    for (int i = 0; i < count; ++i) {
      model.alphas.push_back(alphas.at<double>(i));
      model.filters.push_back(filters.row(i).reshape(1, model.size).clone());
    }
  } catch (const cv::Exception& error) {
    malformed(name, "not a readable FoE model (" + std::string(error.err) + ")");
  }
  check(model, name);
  return model;
}

std::string serialize_foe_model(const FoeModel& model) {
  cv::FileStorage storage(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  storage << "format_version" << FoeModel::kFormatVersion;
  storage << "name" << model.name;
  storage << "filter_size" << model.size;
  storage << "filter_count" << model.count();
  storage << "input_scale" << model.input_scale;
  storage << "known_rms" << static_cast<int>(model.known_rms);
  storage << "normalisation" << model.normalisation;
  storage << "training" << model.training;
  storage << "alphas" << cv::Mat(model.alphas, true).reshape(1, 1);
  cv::Mat filters(model.count(), model.size * model.size, CV_64F);
  for (int i = 0; i < model.count(); ++i) {
    model.filters[i].reshape(1, 1).copyTo(filters.row(i));
  }
  storage << "filters" << filters;
  return storage.releaseAndGetString();
}

std::vector<std::string> shipped_foe_models() {
  std::vector<std::string> names;
  for (const ShippedModel& model : shipped_models()) names.emplace_back(model.name);
  return names;
}

FoeModel load_foe_model(const std::string& name_or_path) {
  for (const ShippedModel& model : shipped_models()) {
    if (name_or_path == model.name) return parse_foe_model(model.text, model.name);
  }
  std::ifstream file(name_or_path, std::ios::binary);
  if (!file) {
    std::string known;
    for (const std::string& name : shipped_foe_models())
      known += (known.empty() ? "" : ", ") + name;
    throw InvalidInput(name_or_path + ": neither a shipped FoE model (" + known +
                       ") nor a readable file");
  }
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  return parse_foe_model(text, name_or_path);
}

double foe_input_divisor(const FoeModel& model, const cv::Mat& image, const cv::Mat& mask) {
  if (!model.known_rms) return 1;
  cv::Mat values;
  image.convertTo(values, CV_64F);
  double sum = 0;  // in row order, the same whatever OpenCV's threads do
  int count = 0;
  for (int row = 0; row < values.rows; ++row) {
    for (int col = 0; col < values.cols; ++col) {
      if (mask.at<std::uint8_t>(row, col)) continue;
      sum += values.at<double>(row, col) * values.at<double>(row, col);
      ++count;
    }
  }
  const double rms = count > 0 ? std::sqrt(sum / count) : 0;
  return rms > 0 ? rms : 1;
}

namespace {

// Cliques as runs of filter centres along a row: (row, first column, one past the last).
struct CliqueRun {
  int row, begin, end;
};

// Every clique whose filter lies inside an image of `size` (filters of radius r).
std::vector<CliqueRun> valid_cliques(cv::Size size, int r) {
  std::vector<CliqueRun> runs;
  if (size.width <= 2 * r) return runs;
  for (int row = r; row < size.height - r; ++row) runs.push_back({row, r, size.width - r});
  return runs;
}

// The valid cliques whose filter covers at least one pixel of `mask` (the others do not change
// when the masked pixels do).
std::vector<CliqueRun> cliques_touching(const cv::Mat& mask, int r) {
  cv::Mat touched;
  cv::dilate(mask, touched, cv::Mat::ones(2 * r + 1, 2 * r + 1, CV_8U));
  std::vector<CliqueRun> runs;
  for (int row = r; row < mask.rows - r; ++row) {
    const std::uint8_t* line = touched.ptr<std::uint8_t>(row);
    for (int col = r; col < mask.cols - r;) {
      if (!line[col]) {
        ++col;
        continue;
      }
      const int begin = col;
      while (col < mask.cols - r && line[col]) ++col;
      runs.push_back({row, begin, col});
    }
  }
  return runs;
}

// y = J ⋆ x at the cliques of `runs`, 0 elsewhere. Plain loops that sum the taps in one order,
// so results are the same at any thread count (cv::filter2D's are not); the inner loops vectorise.
cv::Mat correlate(const cv::Mat& x, const cv::Mat& kernel, const std::vector<CliqueRun>& runs) {
  const int r = kernel.rows / 2;
  cv::Mat y = cv::Mat::zeros(x.size(), CV_64F);
  for (const CliqueRun& run : runs) {
    double* out = y.ptr<double>(run.row);
    for (int dy = -r; dy <= r; ++dy) {
      const double* in = x.ptr<double>(run.row + dy);
      for (int dx = -r; dx <= r; ++dx) {
        const double weight = kernel.at<double>(dy + r, dx + r);
        for (int col = run.begin; col < run.end; ++col) out[col] += weight * in[col + dx];
      }
    }
  }
  return y;
}

// sum += Jᵀ z, z read at the cliques of `runs` only.
void add_correlation_adjoint(const cv::Mat& z, const cv::Mat& kernel,
                             const std::vector<CliqueRun>& runs, cv::Mat& sum) {
  const int r = kernel.rows / 2;
  for (const CliqueRun& run : runs) {
    const double* in = z.ptr<double>(run.row);
    for (int dy = -r; dy <= r; ++dy) {
      double* out = sum.ptr<double>(run.row + dy);
      for (int dx = -r; dx <= r; ++dx) {
        const double weight = kernel.at<double>(dy + r, dx + r);
        for (int col = run.begin; col < run.end; ++col) out[col + dx] += weight * in[col];
      }
    }
  }
}

// The weights w_i of the quadratic forms Σ_c w_ic (J_i ⋆ x)_c² / 2 that inference builds, at every
// clique: pixel-major ([pixel · count + i]), 0 off the cliques.
struct CliqueWeights {
  std::vector<double> half_quadratic;  // α_i / (1 + y²/2): the bound of Geman & Yang
  std::vector<double> curvature;  // α_i ρ''(y) = α_i (1 − y²/2) / (1 + y²/2)²: the Hessian
};

// E over the cliques of `runs` (Roth & Black's eq. for the FoE energy), ∇E into `gradient` and the
// clique weights at x into `weights`.
double energy_over(const FoeModel& model, const cv::Mat& x, const std::vector<CliqueRun>& runs,
                   cv::Mat* gradient, CliqueWeights* weights = nullptr) {
  if (gradient) *gradient = cv::Mat::zeros(x.size(), CV_64F);
  const int count = model.count();
  if (weights) {
    weights->half_quadratic.assign(x.total() * count, 0.0);
    weights->curvature.assign(x.total() * count, 0.0);
  }
  double energy = 0;
  for (int i = 0; i < count; ++i) {
    const cv::Mat kernel = model.filters[i] * model.input_scale;
    cv::Mat y = correlate(x, kernel, runs);
    const double alpha = model.alphas[i];
    for (const CliqueRun& run : runs) {
      double* line = y.ptr<double>(run.row);
      for (int col = run.begin; col < run.end; ++col) {
        const double half_square = 0.5 * line[col] * line[col];
        energy += alpha * std::log1p(half_square);
        const double weight = alpha / (1 + half_square);
        if (weights) {
          const size_t at = (static_cast<size_t>(run.row) * x.cols + col) * count + i;
          weights->half_quadratic[at] = weight;
          weights->curvature[at] = weight * (1 - half_square) / (1 + half_square);
        }
        line[col] *= weight;  // ψ_i(y), the expert's influence
      }
    }
    if (gradient) add_correlation_adjoint(y, kernel, runs, *gradient);
  }
  return energy;
}

void check_energy_argument(const cv::Mat& x) {
  CV_Assert(x.type() == CV_64FC1);
}

}  // namespace

cv::Mat foe_response(const cv::Mat& x, const cv::Mat& kernel) {
  check_energy_argument(x);
  return correlate(x, kernel, valid_cliques(x.size(), kernel.rows / 2));
}

cv::Mat foe_adjoint(const cv::Mat& z, const cv::Mat& kernel) {
  check_energy_argument(z);
  cv::Mat sum = cv::Mat::zeros(z.size(), CV_64F);
  add_correlation_adjoint(z, kernel, valid_cliques(z.size(), kernel.rows / 2), sum);
  return sum;
}

double foe_energy(const FoeModel& model, const cv::Mat& x, cv::Mat* gradient) {
  check_energy_argument(x);
  return energy_over(model, x, valid_cliques(x.size(), model.size / 2), gradient);
}

double foe_energy_of_unknowns(const FoeModel& model, const cv::Mat& x, const cv::Mat& mask,
                              cv::Mat* gradient) {
  check_energy_argument(x);
  CV_Assert(mask.type() == CV_8UC1 && mask.size() == x.size());
  return energy_over(model, x, cliques_touching(mask, model.size / 2), gradient);
}

namespace {

// The unknown pixels of `mask` in row-major order, and each one's number (−1 elsewhere).
struct Unknowns {
  explicit Unknowns(const cv::Mat& mask) : index(mask.size(), CV_32S, cv::Scalar(-1)) {
    cv::findNonZero(mask, pixels);
    for (size_t k = 0; k < pixels.size(); ++k) index.at<int>(pixels[k]) = static_cast<int>(k);
  }
  int at(cv::Point p) const {
    return p.x < 0 || p.y < 0 || p.x >= index.cols || p.y >= index.rows ? -1 : index.at<int>(p);
  }
  std::vector<cv::Point> pixels;
  cv::Mat index;  // CV_32S
};

// The matrices A = Σ_i Σ_c w_ic J_ic J_icᵀ over the unknowns that inference factorises. As
// ρ(y) = log(1 + y²/2) has ρ'' ≤ 1, w = α_i bounds E around every point (A is then the Hessian of
// the Gaussian field with the same filters); as ρ is concave in y², the half-quadratic weights
// w = α_i / (1 + y²/2) at the current responses bound it more tightly around the current point
// (Geman & Yang): either way x − A⁻¹∇E lowers E. With w = α_i ρ''(y), A is the Hessian. Entries
// A(p, p + d) = Σ_i Σ_t w_i(p − t) K_i(t) K_i(t + d), with K_i the scaled kernels, over the
// (4r + 1)² offsets d of the stencil.
class FilterMatrix {
 public:
  FilterMatrix(const FoeModel& model, const Unknowns& unknowns) : unknowns_(unknowns) {
    const int r = model.size / 2, count = model.count();
    count_ = count;
    // For each stencil offset d, the taps t with t + d in the kernel and the products
    // K_i(t) K_i(t + d) of every filter.
    for (int dy = -2 * r; dy <= 2 * r; ++dy) {
      for (int dx = -2 * r; dx <= 2 * r; ++dx) {
        Offset offset;
        for (int ty = std::max(-r, -r - dy); ty <= std::min(r, r - dy); ++ty) {
          for (int tx = std::max(-r, -r - dx); tx <= std::min(r, r - dx); ++tx) {
            offset.taps.emplace_back(tx, ty);
            for (int i = 0; i < count; ++i) {
              const double scale = model.input_scale * model.input_scale;
              offset.products.push_back(scale * model.filters[i].at<double>(ty + r, tx + r) *
                                        model.filters[i].at<double>(ty + dy + r, tx + dx + r));
            }
          }
        }
        offsets_.push_back(std::move(offset));
      }
    }
    const int n = static_cast<int>(unknowns.pixels.size()), side = 4 * r + 1;
    std::vector<Eigen::Triplet<double>> pattern;
    for (int column = 0; column < n; ++column) {
      for (int d = 0; d < side * side; ++d) {
        const cv::Point p = unknowns.pixels[column] + cv::Point(d % side - 2 * r, d / side - 2 * r);
        const int row = unknowns.at(p);
        if (row >= column) {  // the lower triangle: A is symmetric
          pattern.emplace_back(row, column, 1.0);
          entry_offsets_.push_back(d);
        }
      }
    }
    matrix_.resize(n, n);
    matrix_.setFromTriplets(pattern.begin(), pattern.end());  // keeps the column-major order
    matrix_.makeCompressed();
  }

  // The lower triangle of A for clique weights (pixel-major, as in CliqueWeights), with `ridge`
  // added to the diagonal.
  const Eigen::SparseMatrix<double>& assemble(const std::vector<double>& weights, double ridge) {
    const int cols = unknowns_.index.cols, rows = unknowns_.index.rows;
    double* values = matrix_.valuePtr();
    const int* starts = matrix_.outerIndexPtr();
    for (int column = 0; column < matrix_.outerSize(); ++column) {
      const cv::Point p = unknowns_.pixels[column];
      for (int k = starts[column]; k < starts[column + 1]; ++k) {
        const Offset& offset = offsets_[entry_offsets_[k]];
        double sum = matrix_.innerIndexPtr()[k] == column ? ridge : 0;
        const double* product = offset.products.data();
        for (const cv::Point& t : offset.taps) {
          const cv::Point centre = p - t;  // of the clique; none outside the image
          if (centre.x >= 0 && centre.y >= 0 && centre.x < cols && centre.y < rows) {
            const double* w = &weights[(centre.y * cols + centre.x) * count_];
            for (int i = 0; i < count_; ++i) sum += w[i] * product[i];
          }
          product += count_;
        }
        values[k] = sum;
      }
    }
    return matrix_;
  }

 private:
  struct Offset {
    std::vector<cv::Point> taps;
    std::vector<double> products;  // [tap · count + filter]
  };
  const Unknowns& unknowns_;
  int count_ = 0;
  std::vector<Offset> offsets_;
  std::vector<int> entry_offsets_;  // the stencil offset of each stored entry
  Eigen::SparseMatrix<double> matrix_;
};

// E, ∇E over the unknowns and the clique weights at a point.
struct Evaluation {
  double energy = 0;
  Eigen::VectorXd gradient;
  CliqueWeights weights;
};

Evaluation evaluate(const FoeModel& model, const cv::Mat& x, const std::vector<CliqueRun>& runs,
                    const Unknowns& unknowns) {
  Evaluation evaluation;
  cv::Mat gradient;
  evaluation.energy = energy_over(model, x, runs, &gradient, &evaluation.weights);
  evaluation.gradient.resize(unknowns.pixels.size());
  for (size_t k = 0; k < unknowns.pixels.size(); ++k) {
    evaluation.gradient[k] = gradient.at<double>(unknowns.pixels[k]);
  }
  return evaluation;
}

}  // namespace

namespace {

// What foe_map and foe_hessian_of_unknowns share: the unknowns, the cliques that see them, and
// the matrices of quadratic forms over them.
struct InferenceProblem {
  InferenceProblem(const FoeModel& model, const cv::Mat& mask)
      : unknowns(mask), runs(cliques_touching(mask, model.size / 2)), matrices(model, unknowns) {}
  Unknowns unknowns;
  std::vector<CliqueRun> runs;
  FilterMatrix matrices;
};

// Keeps A definite where the filters cannot see an unknown (a mask covering the image).
double ridge_of(const FoeModel& model) {
  double ridge = 0;
  for (double alpha : model.alphas) ridge += 1e-12 * alpha * model.input_scale * model.input_scale;
  return ridge;
}

// foe_map's newton method on x.
cv::Mat newton_map(const FoeModel& model, cv::Mat x, const cv::Mat& mask,
                   const FoeMapOptions& options) {
  InferenceProblem problem(model, mask);
  const std::vector<cv::Point>& unknowns = problem.unknowns.pixels;
  const int count = model.count();
  const double ridge = ridge_of(model);
  std::vector<double> gaussian(x.total() * count, 0.0);
  for (const CliqueRun& run : problem.runs) {
    for (int col = run.begin; col < run.end; ++col) {
      std::copy(model.alphas.begin(), model.alphas.end(),
                gaussian.begin() + (static_cast<size_t>(run.row) * x.cols + col) * count);
    }
  }
  // CHOLMOD's supernodal Cholesky: on the (4r + 1)²-point stencils of 5×5 filters it factorises
  // nine times faster than Eigen's simplicial LDLᵀ (256² pixels, 15 % unknown: 0.2 s against 1.8
  // s).
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
  Evaluation current = evaluate(model, x, problem.runs, problem.unknowns);
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
      next = evaluate(model, trial, problem.runs, problem.unknowns);
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
  std::vector<double> symbol(kSteps * kSteps, 0.0), laplacian;
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
// order at any thread count.
class BlockedEnergy {
 public:
  BlockedEnergy(const FoeModel& model, const cv::Mat& mask, const Unknowns& unknowns)
      : unknowns_(unknowns), alphas_(model.alphas) {
    const int r = model.size / 2, taps = model.size * model.size;
    for (const CliqueRun& run : cliques_touching(mask, r)) {
      for (int col = run.begin; col < run.end; ++col) centres_.push_back(run.row * mask.cols + col);
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
      // is below 6e76 and a product of four stays finite; a quarter of the logarithms.
      for (int c = 0; c < block; ++c) {
        float* y = responses_.col(c).data();
        if (c % 4 == 0) std::fill(product.begin(), product.end(), 1.0);
        for (int i = 0; i < count; ++i) {
          const double response = y[i], factor = 1 + 0.5 * response * response;
          product[i] *= factor;
          y[i] = static_cast<float>(alphas_[i] * response / factor);  // ψ_i(y)
        }
        if (c % 4 == 3 || c == block - 1) {
          for (int i = 0; i < count; ++i) energy += alphas_[i] * std::log(product[i]);
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
  std::vector<int> centres_;  // of the cliques, as offsets into the image's data
  std::vector<int> offsets_;  // of the taps from the centre, row-major over the filter
  Eigen::MatrixXf filters_;   // count × taps, scaled by the model's input scale
  Eigen::MatrixXf patches_, responses_, back_;
  cv::Mat full_gradient_;
};

// p(A)·r ≈ A⁻¹r for an SPD matrix A with spectrum in [1, highest]: a fixed number of Chebyshev
// semi-iteration steps from 0 (Saad, Iterative Methods, 12.1), enough for a relative error of
// 1/10 at most. p(A) is a polynomial in A, so it is symmetric, and positive as |1 − λp(λ)| < 1 on
// the spectrum: an SPD operator, cheaper than a factorisation when A is well-conditioned (I + tL,
// condition 1 + 8t, needs 9 steps for both shipped models, whose t is 3.63).
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
// L + tL², a 13-point matrix that alone costs most of the time budget), hence the loop here.
cv::Mat lbfgs_map(const FoeModel& model, const LaplacianPolynomial& polynomial, cv::Mat x,
                  const cv::Mat& mask, const FoeMapOptions& options) {
  constexpr int kMemory = 10;       // correction pairs kept
  constexpr double kArmijo = 1e-4;  // sufficient decrease
  const Unknowns unknowns(mask);
  const int n = static_cast<int>(unknowns.pixels.size());
  const LaplaceSystem laplace = laplace_system(x, mask);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> laplacian(laplace.matrix);
  if (laplacian.info() != Eigen::Success) {
    throw ProcessingError("foe: the preconditioner could not be factorised");
  }
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

  BlockedEnergy energy_of(model, mask, unknowns);
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
                            const FoeMapOptions& options) {
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
    const cv::Mat part = lbfgs_map(model, polynomial, x(box).clone(), unknowns, options);
    part.copyTo(x(box), unknowns);
  }
  return x;
}

}  // namespace

cv::Mat foe_map(const FoeModel& model, const cv::Mat& image, const cv::Mat& mask,
                const FoeMapOptions& options) {
  check_energy_argument(image);
  CV_Assert(mask.type() == CV_8UC1 && mask.size() == image.size());
  cv::Mat x = image.clone();
  const int unknowns = cv::countNonZero(mask);
  if (unknowns == 0) return x;
  if (unknowns == static_cast<int>(mask.total())) return x.setTo(0);
  if (options.start_from_image) {
    if (!cv::checkRange(x)) throw InvalidInput("foe_map: the start is not finite");
  } else {
    x.setTo(0, mask);
  }
  return options.method == FoeMapMethod::newton ? newton_map(model, x, mask, options)
                                                : lbfgs_map_by_groups(model, x, mask, options);
}

Eigen::SparseMatrix<double> foe_hessian_of_unknowns(const FoeModel& model, const cv::Mat& x,
                                                    const cv::Mat& mask) {
  check_energy_argument(x);
  CV_Assert(mask.type() == CV_8UC1 && mask.size() == x.size());
  InferenceProblem problem(model, mask);
  const Evaluation at_x = evaluate(model, x, problem.runs, problem.unknowns);
  return problem.matrices.assemble(at_x.weights.curvature, 0).selfadjointView<Eigen::Lower>();
}

}  // namespace rangefill
