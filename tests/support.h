// Helpers shared by the tests: built meshes and access to ../shared.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "rangefill/mesh.h"

namespace rangefill::testing {

/// ../shared/data, or nullopt when it is absent (the caller then GTEST_SKIP()s with a message).
std::optional<std::filesystem::path> shared_data_dir();

/// A fresh empty directory under the system temp directory, unique per call.
std::filesystem::path temporary_directory(const std::string& stem);

/// The unit cube [0,1]³ as 12 outward-facing triangles on 8 vertices.
Mesh make_cube();

/// A flat n×n grid of quads (2 triangles each) in z = 0 with spacing 1, counter-clockwise seen from
/// +z.
Mesh make_grid(int n);

}  // namespace rangefill::testing

/// Skips the current test with a message when ../shared/data is absent; else binds `dir` to it.
#define RANGEFILL_REQUIRE_SHARED(dir)                                                  \
  const auto dir##_optional = ::rangefill::testing::shared_data_dir();                 \
  if (!dir##_optional) GTEST_SKIP() << "../shared/data is absent: skipping this test"; \
  const std::filesystem::path dir = *dir##_optional
