#include "research.h"

namespace rangefill::cli {

void add_research_commands(CLI::App& app, Runner& runner) {
  add_bench_command(app, runner);
  add_depth_bench_command(app, runner);
  add_train_foe_command(app, runner);
  add_patch_bench_command(app, runner);
}

void add_patch_options(CLI::App* command, HoleSampleOptions& samples) {
  command->add_option("--patches", samples.patches.count, "Patches per mesh")
      ->capture_default_str();
  command->add_option("--patch-size", samples.patches.size, "Patch size in pixels")
      ->capture_default_str();
  command->add_option("--seed", samples.patches.seed, "Seed of patches and masks")
      ->capture_default_str();
}

}  // namespace rangefill::cli
