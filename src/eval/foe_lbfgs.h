// Internal: the L-BFGS of FoE training (Ceres' GradientProblemSolver), in a module of its own,
// librangefill_foe_lbfgs.so, installed beside librangefill_eval.so, which eval/foe_training.cpp
// loads (dlopen) when it first trains: Ceres and its libraries (glog, BLAS, LAPACK) load only then.
#pragma once

#include <string>
#include <vector>

#include "rangefill/eval/foe_training.h"

namespace rangefill::foe_lbfgs {

constexpr const char* kModule = "librangefill_foe_lbfgs.so";
constexpr const char* kEntry = "rangefill_foe_lbfgs";

/// The module's entry: minimises `objective` over θ from `theta` (which receives the result) by
/// options.iterations L-BFGS iterations at most, within options.max_seconds, calling
/// options.progress after each; `iterations` and `stop` (Ceres' message) say how it ended.
using Entry = void (*)(const FoeObjective& objective, const FoeTrainingOptions& options,
                       std::vector<double>& theta, int& iterations, std::string& stop);

}  // namespace rangefill::foe_lbfgs
