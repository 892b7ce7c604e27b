#include "rangefill/inpaint/foe_energy.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "inpaint/foe_terms.h"
#include "rangefill/core/errors.h"
#include "rangefill/inpaint/harmonic.h"

namespace rangefill {

namespace foe_terms {

std::vector<CliqueRun> valid_cliques(cv::Size size, int r) {
  std::vector<CliqueRun> runs;
  if (size.width <= 2 * r) return runs;
  for (int row = r; row < size.height - r; ++row) runs.push_back({row, r, size.width - r});
  return runs;
}

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

double energy_over(const FoeModel& model, const cv::Mat& x, const std::vector<CliqueRun>& runs,
                   cv::Mat* gradient, CliqueWeights* weights, const cv::Mat& clique_weights) {
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
    for (const CliqueRun& run : runs) {
      double* line = y.ptr<double>(run.row);
      const double* clique_weight =
          clique_weights.empty() ? nullptr : clique_weights.ptr<double>(run.row);
      for (int col = run.begin; col < run.end; ++col) {
        const double alpha = model.alphas[i] * (clique_weight ? clique_weight[col] : 1);
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

void check_clique_weights(const cv::Mat& clique_weights, const cv::Mat& x) {
  CV_Assert(clique_weights.empty() ||
            (clique_weights.type() == CV_64FC1 && clique_weights.size() == x.size()));
}

Evaluation evaluate(const FoeModel& model, const cv::Mat& x, const std::vector<CliqueRun>& runs,
                    const Unknowns& unknowns, const cv::Mat& clique_weights) {
  Evaluation evaluation;
  cv::Mat gradient;
  evaluation.energy = energy_over(model, x, runs, &gradient, &evaluation.weights, clique_weights);
  evaluation.gradient.resize(unknowns.pixels.size());
  for (size_t k = 0; k < unknowns.pixels.size(); ++k) {
    evaluation.gradient[k] = gradient.at<double>(unknowns.pixels[k]);
  }
  return evaluation;
}

}  // namespace foe_terms

using namespace foe_terms;

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
                              cv::Mat* gradient, const cv::Mat& clique_weights) {
  check_energy_argument(x);
  CV_Assert(mask.type() == CV_8UC1 && mask.size() == x.size());
  check_clique_weights(clique_weights, x);
  return energy_over(model, x, cliques_touching(mask, model.size / 2), gradient, nullptr,
                     clique_weights);
}

cv::Mat foe_clique_weights(const cv::Mat& guide, int size, float sigma) {
  if (guide.type() != CV_32FC3 || !(sigma > 0)) {
    throw InvalidInput("foe: the guide must be CV_32FC3 and its sigma above 0");
  }
  const int r = size / 2;
  cv::Mat weights(guide.size(), CV_64F, cv::Scalar(1));
  for (int row = r; row < guide.rows - r; ++row) {
    for (int col = r; col < guide.cols - r; ++col) {
      const cv::Vec3f& centre = guide.at<cv::Vec3f>(row, col);
      float least = 1;
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          least = std::min(least,
                           guide_affinity(centre, guide.at<cv::Vec3f>(row + dy, col + dx), sigma));
        }
      }
      weights.at<double>(row, col) = least;
    }
  }
  return weights;
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
