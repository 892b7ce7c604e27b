#include "cli.h"

#include <unistd.h>

#include <iostream>
#include <sstream>

namespace rangefill::cli {

Mesh load_mesh(const std::string& path) {
  ReadResult result = read_mesh(path);
  for (const std::string& warning : result.warnings) std::cerr << "warning: " << warning << "\n";
  return std::move(result.mesh);
}

void set_fallbacks(const std::string& list, RepairOptions& options) {
  options.fallback_front = options.fallback_least_area = false;
  if (list == "none") return;
  std::stringstream stream(list);
  for (std::string item; std::getline(stream, item, ',');) {
    if (item == "front") {
      options.fallback_front = true;
    } else if (item == "least-area") {
      options.fallback_least_area = true;
    } else {
      throw UsageError("--fallback: unknown '" + item + "' (expected front, least-area or none)");
    }
  }
}

bool stdout_is_terminal() {
  return ::isatty(STDOUT_FILENO) == 1;
}
bool stderr_is_terminal() {
  return ::isatty(STDERR_FILENO) == 1;
}

std::string join(const std::vector<std::string>& items) {
  std::string joined;
  for (const std::string& item : items) joined += (joined.empty() ? "" : ", ") + item;
  return joined;
}

void print_json(const nlohmann::json& value) {
  std::cout << value.dump(2) << "\n";
}

}  // namespace rangefill::cli
