// rangefill train-foe: fit a Fields-of-Experts model to depth patches cut from meshes.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli.h"
#include "rangefill/eval/foe_training.h"
#include "rangefill/eval/patches.h"
#include "rangefill/inpaint/foe_model.h"
#include "rangefill/io/mesh_io.h"
#include "research.h"

namespace rangefill::cli {

namespace {

namespace fs = std::filesystem;

struct TrainCommand {
  std::vector<std::string> meshes;
  std::string validation = kValidationMeshes, output, name = "depth", initial_model;
  HoleSampleOptions samples;
  FoeTrainingOptions training;
};

// Samples of every mesh, split by mesh name into training and validation.
void cut_samples(const TrainCommand& command, std::vector<HoleSample>& training,
                 std::vector<HoleSample>& validation, std::string& data) {
  const std::vector<std::string> held_out = split_list(command.validation);
  int training_meshes = 0;
  for (const fs::path& file : mesh_files(command.meshes)) {
    const std::string name = file.filename().string();
    const bool validating = std::count(held_out.begin(), held_out.end(), name) > 0;
    const std::vector<HoleSample> samples =
        hole_samples(load_mesh(file.string()), name, command.samples);
    (validating ? validation : training)
        .insert((validating ? validation : training).end(), samples.begin(), samples.end());
    training_meshes += !validating;
    std::printf("%-20s %3zu patches (%s)\n", name.c_str(), samples.size(),
                validating ? "validation" : "training");
    std::fflush(stdout);
  }
  const PatchOptions& patches = command.samples.patches;
  std::ostringstream text;
  text << training.size() << " training patches from " << training_meshes << " meshes, "
       << validation.size() << " validation patches from " << command.validation << "; "
       << patches.size << "x" << patches.size << " pixels at q = " << patches.beta
       << " d_m, blob masks " << command.samples.min_hole * 100 << "-"
       << command.samples.max_hole * 100 << "% of the pixels, seed " << patches.seed;
  data = text.str();
}

int run_train(const TrainCommand& command) {
  std::vector<HoleSample> training, validation;
  std::string data;
  cut_samples(command, training, validation, data);
  if (training.empty() || validation.empty()) {
    throw UsageError("train-foe: need training and validation patches (see --validation)");
  }
  // The model as written: what it expects and how it was made (`state`: the losses, or a
  // checkpoint's iteration).
  const auto describe = [&](FoeModel model, const std::string& state) {
    model.name = command.name;
    model.normalisation =
        "the residual a back-end receives in rangefill's pipeline: zone depth normalised to [0, 1] "
        "(eq. 7-8) minus the quadric fitted to the known pixels within 3 px of the hole";
    model.training =
        "loss-specific: mean squared error at the masked pixels of the MAP estimate from the "
        "harmonic fill, gradient by implicit differentiation, L-BFGS over the filters (DCT basis "
        "without DC) and log alphas; " +
        data + "; " + state + "; command: " + command_line();
    return serialize_foe_model(model);
  };
  FoeTrainingOptions options = command.training;
  if (!command.initial_model.empty()) options.initial_model = load_foe_model(command.initial_model);
  options.progress = [&](int iteration, double loss, double seconds, const FoeModel& model) {
    std::printf("iteration %4d  loss %.6e  %7.1f s\n", iteration, loss, seconds);
    std::fflush(stdout);
    write_file_atomically(
        describe(model, "checkpoint after iteration " + std::to_string(iteration) +
                            ", training loss " + std::to_string(loss)),
        command.output);
  };
  const FoeTraining result = train_foe(training, validation, options);
  std::ostringstream state;
  state << "loss " << result.training_loss_start << " -> " << result.training_loss_end
        << " (validation " << result.validation_loss_start << " -> " << result.validation_loss_end
        << "), " << result.iterations << " iterations, " << static_cast<int>(result.seconds)
        << " s";
  write_file_atomically(describe(result.model, state.str()), command.output);
  std::printf("%s\nvalidation loss %.6e -> %.6e; wrote %s\n", result.stop.c_str(),
              result.validation_loss_start, result.validation_loss_end, command.output.c_str());
  return kOk;
}

}  // namespace

void add_train_foe_command(CLI::App& app, Runner& runner) {
  auto command = std::make_shared<TrainCommand>();
  CLI::App* sub = app.add_subcommand(
      "train-foe", "Fit a Fields-of-Experts model to depth patches cut from meshes");
  sub->add_option("--meshes", command->meshes, "Meshes, or directories of them")->required();
  sub->add_option("--validation", command->validation,
                  "File names of the meshes held out for validation")
      ->capture_default_str();
  sub->add_option("-o,--output", command->output,
                  "The model file to write (YAML); rewritten after each iteration")
      ->required();
  sub->add_option("--name", command->name, "The model's name")->capture_default_str();
  sub->add_option("--size", command->training.size, "Filter size (odd)")->capture_default_str();
  sub->add_option("--count", command->training.count, "Number of filters")->capture_default_str();
  sub->add_option("--iterations", command->training.iterations, "L-BFGS iterations")
      ->capture_default_str();
  add_patch_options(sub, command->samples);
  sub->add_option("--max-seconds", command->training.max_seconds,
                  "Stop after this many seconds (0: no limit)")
      ->capture_default_str();
  sub->add_option("--known-rms", command->training.known_rms,
                  "Divide the model's inputs by the RMS of their known pixels")
      ->capture_default_str();
  sub->add_option("--init", command->initial_model,
                  "Start from this model's filters and weights (a shipped model or a file)");
  sub->add_option("--threads", command->training.threads, "Threads")->capture_default_str();
  sub->callback([command, &runner] { runner = [command] { return run_train(*command); }; });
}

}  // namespace rangefill::cli
