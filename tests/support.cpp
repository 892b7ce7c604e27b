#include "support.h"

#include <atomic>

#include <unistd.h>

namespace rangefill::testing {

namespace fs = std::filesystem;

std::optional<fs::path> shared_data_dir() {
  const fs::path dir = fs::path(RANGEFILL_SHARED_DIR) / "data";
  if (fs::is_directory(dir / "meshes")) return dir;
  return std::nullopt;
}

fs::path temporary_directory(const std::string& stem) {
  static std::atomic<int> counter{0};
  const fs::path dir =
      fs::temp_directory_path() /
      ("rangefill-" + stem + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

Mesh make_cube() {
  std::vector<Vec3> positions;
  for (int i = 0; i < 8; ++i) positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const std::vector<Triangle> triangles = {
      {0, 2, 1}, {1, 2, 3},  // z = 0, facing -z
      {4, 5, 6}, {5, 7, 6},  // z = 1
      {0, 1, 4}, {1, 5, 4},  // y = 0
      {2, 6, 3}, {3, 6, 7},  // y = 1
      {0, 4, 2}, {2, 4, 6},  // x = 0
      {1, 3, 5}, {3, 7, 5},  // x = 1
  };
  return make_mesh(positions, triangles);
}

Mesh make_grid(int n) {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  for (int y = 0; y <= n; ++y) {
    for (int x = 0; x <= n; ++x) positions.emplace_back(x, y, 0.0);
  }
  auto id = [n](int x, int y) { return y * (n + 1) + x; };
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      triangles.push_back({id(x, y), id(x + 1, y), id(x + 1, y + 1)});
      triangles.push_back({id(x, y), id(x + 1, y + 1), id(x, y + 1)});
    }
  }
  return make_mesh(positions, triangles);
}

}  // namespace rangefill::testing
