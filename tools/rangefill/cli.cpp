#include "cli.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

#include "rangefill/core/errors.h"
#include "rangefill/inpaint/foe_model.h"
#include "rangefill/inpaint/inpainters.h"

namespace rangefill::cli {

Mesh load_mesh(const std::string& path, const ReadOptions& options) {
  ReadResult result = read_mesh(path, options);
  for (const std::string& warning : result.warnings) std::cerr << "warning: " << warning << "\n";
  return std::move(result.mesh);
}

FillerChain chain_from_arguments(const std::string& filler, const std::string& fallback,
                                 const FillerOptions& fillers) {
  try {
    return make_filler_chain(filler, fallback, fillers);
  } catch (const InvalidInput& error) {
    throw UsageError(std::string("--filler/--fallback: ") + error.what());
  }
}

FillerChain candidates_from_arguments(const CLI::App& command, const std::string& select,
                                      const FillerOptions& fillers) {
  if (command.count("--select") == 0 &&
      (command.count("--filler") || command.count("--fallback"))) {
    return {};
  }
  try {
    return make_fillers(select, fillers);
  } catch (const InvalidInput& error) {
    throw UsageError(std::string("--select: ") + error.what());
  }
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

std::filesystem::path color_image_of(const std::filesystem::path& dir,
                                     const std::filesystem::path& frame) {
  for (const char* extension : {".png", ".jpg", ".jpeg", ".tif", ".tiff"}) {
    std::filesystem::path candidate = dir / (frame.stem().string() + extension);
    if (std::filesystem::exists(candidate)) return candidate;
  }
  return {};
}

std::vector<std::filesystem::path> files_from_arguments(
    const std::vector<std::string>& arguments,
    const std::function<bool(const std::filesystem::path&)>& wanted) {
  std::vector<std::filesystem::path> files;
  for (const std::string& argument : arguments) {
    if (!std::filesystem::is_directory(argument)) {
      files.emplace_back(argument);
      continue;
    }
    std::vector<std::filesystem::path> found;
    for (const std::filesystem::directory_entry& entry :
         std::filesystem::directory_iterator(argument)) {
      if (wanted(entry.path())) found.push_back(entry.path());
    }
    std::sort(found.begin(), found.end());
    files.insert(files.end(), found.begin(), found.end());
  }
  return files;
}

std::vector<std::filesystem::path> mesh_files(const std::vector<std::string>& arguments) {
  return files_from_arguments(arguments, [](const std::filesystem::path& path) {
    const std::string extension = path.extension().string();
    return extension == ".ply" || extension == ".obj" || extension == ".off" || extension == ".stl";
  });
}

double median(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

bool stdout_is_terminal() {
  return ::isatty(STDOUT_FILENO) == 1;
}
bool stderr_is_terminal() {
  return ::isatty(STDERR_FILENO) == 1;
}

namespace {
std::string invocation;   // the command line, for reports that say how they were made
std::mutex output_mutex;  // held while an output is written; the interrupt thread waits for it
std::atomic<bool> interrupted{false};  // set by the interrupt thread before it waits

// After an interrupt: the interrupt thread is about to end the process; start no more work.
[[noreturn]] void wait_for_exit() {
  for (;;) std::this_thread::sleep_for(std::chrono::hours(1));
}
}  // namespace

void handle_interrupts() {
  sigset_t signals;
  sigemptyset(&signals);
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&signals, signal);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread([signals] {
    int signal = 0;
    while (sigwait(&signals, &signal) != 0) {
    }
    interrupted = true;
    std::lock_guard<std::mutex> lock(output_mutex);
    const char message[] = "rangefill: interrupted\n";
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, message, sizeof message - 1);
    std::_Exit(128 + signal);
  }).detach();
}

OutputGuard::OutputGuard() {
  output_mutex.lock();
  if (!interrupted) return;
  output_mutex.unlock();
  wait_for_exit();
}

OutputGuard::~OutputGuard() {
  output_mutex.unlock();
  if (interrupted) wait_for_exit();  // the interrupt takes effect now, not after the next output
}

void set_command_line(int argc, char** argv) {
  invocation.clear();
  for (int i = 0; i < argc; ++i)
    invocation += (i ? " " : "") + std::string(i ? argv[i] : "rangefill");
}

const std::string& command_line() {
  return invocation;
}

std::string join(const std::vector<std::string>& items) {
  std::string joined;
  for (const std::string& item : items) joined += (joined.empty() ? "" : ", ") + item;
  return joined;
}

void check_inpainter(const std::string& spec, const std::string& option) {
  try {
    make_inpainter(spec);
  } catch (const InvalidInput& error) {
    throw UsageError(option + ": " + error.what());
  }
}

std::string inpainter_help() {
  return "Back-end: " + join(inpainter_names()) + ", or foe:MODEL with MODEL one of " +
         join(shipped_foe_models()) + " or a model file";
}

void add_foe_inference_options(CLI::App* sub, InpainterOptions& options) {
  std::vector<std::string> starts = inpainter_names();
  starts.erase(std::find(starts.begin(), starts.end(), "foe"));
  sub->add_option("--foe-start", options.foe.start,
                  "foe: what inference starts from: harmonic (its own Laplace fill) or another "
                  "back-end's fill (E is not convex: the minimum found is the one near the start)")
      ->capture_default_str()
      ->check(CLI::IsMember(starts));
  sub->add_option("--foe-tolerance", options.foe.tolerance,
                  "foe: stop when a step lowers the energy by less than this share of it")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--foe-iterations", options.foe.iterations, "foe: or after this many steps")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
}

void print_json(const nlohmann::json& value) {
  std::cout << value.dump(2) << "\n";
}

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code error;
  return std::filesystem::equivalent(a, b, error);
}

std::pair<int, int> parse_shard(const std::string& text) {
  const size_t slash = text.find('/');
  try {
    size_t used_k = 0, used_n = 0;
    const int k = std::stoi(text.substr(0, slash), &used_k);
    const int n = std::stoi(text.substr(slash + 1), &used_n);
    if (slash != std::string::npos && used_k == slash && used_n == text.size() - slash - 1 &&
        n >= 1 && k >= 0 && k < n) {
      return {k, n};
    }
  } catch (const std::exception&) {
  }
  throw UsageError("--shard: '" + text + "' is not K/N with 0 <= K < N");
}

}  // namespace rangefill::cli
