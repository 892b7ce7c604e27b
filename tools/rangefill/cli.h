// Shared plumbing of the rangefill sub-commands: exit codes, messages, loading, JSON output.
#pragma once

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "rangefill/inpaint/inpainters.h"
#include "rangefill/io/mesh_io.h"
#include "rangefill/repair/filler_options.h"
#include "rangefill/repair/pipeline.h"

namespace rangefill::cli {

/// 0 ok, 2 usage error, 3 unreadable or invalid input, 4 processing failure, 5 partial result
/// (output written, some holes left open).
enum ExitCode { kOk = 0, kUsage = 2, kBadInput = 3, kFailure = 4, kPartial = 5 };

/// An argument that parsed but makes no sense (exit code 2).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// "a,b,,c" → {"a", "b", "c"}.
std::vector<std::string> split_list(const std::string& text);

/// Files named on the command line, directories expanded to the files in them that `wanted`
/// accepts, in name order.
std::vector<std::filesystem::path> files_from_arguments(
    const std::vector<std::string>& arguments,
    const std::function<bool(const std::filesystem::path&)>& wanted);

/// The colour image of depth image `frame` in `dir`: the file of the same stem with an image
/// extension (.png, .jpg, .jpeg, .tif, .tiff), empty if none.
std::filesystem::path color_image_of(const std::filesystem::path& dir,
                                     const std::filesystem::path& frame);

/// files_from_arguments taking the mesh files (.ply, .obj, .off, .stl).
std::vector<std::filesystem::path> mesh_files(const std::vector<std::string>& arguments);

/// The median of `values`; 0 when empty.
double median(std::vector<double> values);

/// The command line as typed (set once by main), for reports that say how they were made.
void set_command_line(int argc, char** argv);
const std::string& command_line();

/// Throws UsageError naming `option` unless make_inpainter accepts `spec` ("foe:MODEL" included).
void check_inpainter(const std::string& spec, const std::string& option);

/// The help text of an --inpainter option.
std::string inpainter_help();

/// --foe-start, --foe-tolerance and --foe-iterations on `sub`, into `options` (whose values are the
/// defaults shown).
void add_foe_inference_options(CLI::App* sub, InpainterOptions& options);

/// "a, b, c" for messages and help texts.
std::string join(const std::vector<std::string>& items);

/// What a sub-command does once its arguments are parsed; returns the exit code.
using Runner = std::function<int()>;

/// Each sub-command registers itself on `app` and, when chosen, stores its work in `runner`.
void add_info_command(CLI::App& app, Runner& runner);
void add_holes_command(CLI::App& app, Runner& runner);
void add_repair_command(CLI::App& app, Runner& runner);
void add_depth_command(CLI::App& app, Runner& runner);

/// RepairOptions::chain from --filler and --fallback (make_filler_chain), each filler made with
/// its part of `fillers`; throws UsageError on an unknown name.
FillerChain chain_from_arguments(const std::string& filler, const std::string& fallback,
                                 const FillerOptions& fillers);

/// RepairOptions::selection's candidates from --select (make_fillers): none when --filler or
/// --fallback is given without --select, so that the chain named fills every hole. Throws
/// UsageError on an unknown name.
FillerChain candidates_from_arguments(const CLI::App& command, const std::string& select,
                                      const FillerOptions& fillers);

/// SIGINT, SIGTERM and SIGHUP do not kill the process where it stands: a thread of their own
/// takes them and exits with 128 + the signal's number, but never while an OutputGuard is held, so
/// that every output is complete or absent and no temporary file is left behind. Call first in
/// main, before any other thread exists (threads inherit the blocked signals).
void handle_interrupts();

/// Held while an output file is written: an interrupt waits until it is gone, and then ends the
/// process before anything else happens.
class OutputGuard {
 public:
  OutputGuard();
  ~OutputGuard();
  OutputGuard(const OutputGuard&) = delete;
  OutputGuard& operator=(const OutputGuard&) = delete;
};

/// Reads a mesh, printing its warnings to stderr as "warning: ..." lines.
Mesh load_mesh(const std::string& path, const ReadOptions& options = {});

/// True when stdout / stderr is a terminal (progress and colour only then).
bool stdout_is_terminal();
bool stderr_is_terminal();

/// Prints JSON to stdout, two-space indented.
void print_json(const nlohmann::json& value);

/// Whether a and b name the same existing file.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// --shard "K/N" (0 <= K < N) as {K, N}; throws UsageError otherwise.
std::pair<int, int> parse_shard(const std::string& text);

/// The items K, K + N, K + 2N, ... of `all`: a shard's share of a job array.
template <typename Item>
std::vector<Item> shard_of(const std::vector<Item>& all, std::pair<int, int> shard) {
  std::vector<Item> share;
  for (size_t i = shard.first; i < all.size(); i += shard.second) share.push_back(all[i]);
  return share;
}

}  // namespace rangefill::cli
