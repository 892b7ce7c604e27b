// The module librangefill_foe_lbfgs.so (eval/foe_lbfgs.h): the only translation unit that
// includes Ceres.
#include "eval/foe_lbfgs.h"

#include <algorithm>
#include <cmath>

#include <ceres/ceres.h>

namespace rangefill::foe_lbfgs {

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

// Reports each iteration with the model of θ as it stands (Ceres updates θ every iteration).
class Progress : public ceres::IterationCallback {
 public:
  Progress(const FoeTrainingOptions& options, const FoeObjective& objective,
           const std::vector<double>& theta)
      : options_(options), objective_(objective), theta_(theta) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    if (options_.progress) {
      options_.progress(summary.iteration, summary.cost, summary.cumulative_time_in_seconds,
                        objective_.model(theta_));
    }
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const FoeTrainingOptions& options_;
  const FoeObjective& objective_;
  const std::vector<double>& theta_;
};

}  // namespace

}  // namespace rangefill::foe_lbfgs

extern "C" __attribute__((visibility("default"))) void rangefill_foe_lbfgs(
    const rangefill::FoeObjective& objective, const rangefill::FoeTrainingOptions& options,
    std::vector<double>& theta, int& iterations, std::string& stop) {
  using namespace rangefill::foe_lbfgs;
  ceres::GradientProblemSolver::Options solver;
  solver.line_search_direction_type = ceres::LBFGS;
  // θ started from a model (Roth & Black's: filters of size ~100) is far from unit scale: scale the
  // L-BFGS Hessian estimate by the curvature seen, not by identity.
  solver.use_approximate_eigenvalue_bfgs_scaling = true;
  solver.max_num_iterations = options.iterations;
  solver.function_tolerance = 1e-9;
  solver.parameter_tolerance = 1e-12;
  // The MAP moves between basins as θ changes, so the objective has small jumps; a line search
  // that has not found a step in 10 tries will not, and more tries and restarts only take time.
  solver.max_num_line_search_step_size_iterations = 10;
  solver.max_num_line_search_direction_restarts = 2;
  if (options.max_seconds > 0) solver.max_solver_time_in_seconds = options.max_seconds;
  solver.logging_type = ceres::SILENT;
  solver.update_state_every_iteration = true;
  Progress progress(options, objective, theta);
  solver.callbacks.push_back(&progress);
  ceres::GradientProblemSolver::Summary summary;
  ceres::GradientProblem problem(new CeresObjective(objective));
  ceres::Solve(solver, problem, theta.data(), &summary);

  iterations = static_cast<int>(summary.iterations.size()) - 1;
  stop = summary.message;
}
