// The research sub-commands (bench, depth-bench, train-foe, patch-bench): what measures the
// fillers and back-ends, built with RANGEFILL_BUILD_RESEARCH (they need rangefill_eval).
#pragma once

#include <CLI/CLI.hpp>

#include "cli.h"
#include "rangefill/eval/patches.h"

namespace rangefill::cli {

/// Registers bench, depth-bench, train-foe and patch-bench on `app`.
void add_research_commands(CLI::App& app, Runner& runner);

void add_bench_command(CLI::App& app, Runner& runner);
void add_depth_bench_command(CLI::App& app, Runner& runner);
void add_train_foe_command(CLI::App& app, Runner& runner);
void add_patch_bench_command(CLI::App& app, Runner& runner);

/// The meshes of ../shared/data/meshes that train-foe holds out and patch-bench scores on.
inline const char* const kValidationMeshes = "bunny.ply,fandisk.ply,homer.ply";

/// --patches, --patch-size and --seed of the commands that cut depth patches from meshes.
void add_patch_options(CLI::App* command, HoleSampleOptions& samples);

}  // namespace rangefill::cli
