#include "rangefill/foe.h"

#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>

#include <ceres/ceres.h>
#include <opencv2/imgproc.hpp>

#include "rangefill/errors.h"
#include "shipped_models.h"

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

// E over the cliques of `runs` (Roth & Black's eq. for the FoE energy), ∇E into `gradient`.
double energy_over(const FoeModel& model, const cv::Mat& x, const std::vector<CliqueRun>& runs,
                   cv::Mat* gradient) {
  if (gradient) *gradient = cv::Mat::zeros(x.size(), CV_64F);
  double energy = 0;
  for (int i = 0; i < model.count(); ++i) {
    const cv::Mat kernel = model.filters[i] * model.input_scale;
    cv::Mat y = correlate(x, kernel, runs);
    const double alpha = model.alphas[i];
    for (const CliqueRun& run : runs) {
      double* line = y.ptr<double>(run.row);
      for (int col = run.begin; col < run.end; ++col) {
        const double half_square = 0.5 * line[col] * line[col];
        energy += alpha * std::log1p(half_square);
        line[col] = alpha * line[col] / (1 + half_square);  // ψ_i(y), the expert's influence
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

// E as a function of the unknown pixels (the rest fixed), for Ceres.
class EnergyOfUnknowns : public ceres::FirstOrderFunction {
 public:
  EnergyOfUnknowns(const FoeModel& model, cv::Mat image, const cv::Mat& mask,
                   std::vector<cv::Point> unknowns)
      : model_(model), image_(std::move(image)), mask_(mask), unknowns_(std::move(unknowns)) {}

  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    for (size_t k = 0; k < unknowns_.size(); ++k) image_.at<double>(unknowns_[k]) = parameters[k];
    cv::Mat full_gradient;
    *cost = foe_energy_of_unknowns(model_, image_, mask_, gradient ? &full_gradient : nullptr);
    if (gradient) {
      for (size_t k = 0; k < unknowns_.size(); ++k) {
        gradient[k] = full_gradient.at<double>(unknowns_[k]);
      }
    }
    return std::isfinite(*cost);
  }
  int NumParameters() const override { return static_cast<int>(unknowns_.size()); }

 private:
  const FoeModel& model_;
  mutable cv::Mat image_;  // Evaluate writes the unknowns into it
  const cv::Mat& mask_;
  std::vector<cv::Point> unknowns_;
};

}  // namespace

cv::Mat foe_map(const FoeModel& model, const cv::Mat& start, const cv::Mat& mask,
                const FoeMapOptions& options) {
  check_energy_argument(start);
  CV_Assert(mask.type() == CV_8UC1 && mask.size() == start.size());
  std::vector<cv::Point> unknowns;
  cv::findNonZero(mask, unknowns);  // row by row
  cv::Mat result = start.clone();
  if (unknowns.empty()) return result;
  std::vector<double> parameters;
  for (const cv::Point& p : unknowns) parameters.push_back(start.at<double>(p));

  ceres::GradientProblemSolver::Options solver;
  solver.line_search_direction_type = ceres::LBFGS;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = options.function_tolerance;
  solver.gradient_tolerance = options.gradient_tolerance;
  solver.logging_type = ceres::SILENT;
  ceres::GradientProblemSolver::Summary summary;
  ceres::GradientProblem problem(new EnergyOfUnknowns(model, start.clone(), mask, unknowns));
  ceres::Solve(solver, problem, parameters.data(), &summary);
  for (size_t k = 0; k < unknowns.size(); ++k) result.at<double>(unknowns[k]) = parameters[k];
  return result;
}

}  // namespace rangefill
