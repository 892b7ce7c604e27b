// The rangefill binary as a user runs it: exit codes, one-line errors, outputs.
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rangefill/io.h"
#include "rangefill/metrics.h"
#include "support.h"

namespace rangefill {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

std::string slurp(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// Runs `rangefill <arguments>` with virtual memory capped at `memory_kb` (0: no cap).
Outcome run(const std::string& arguments, long memory_kb = 0) {
  const fs::path dir = testing::temporary_directory("cli");
  const fs::path out = dir / "out", err = dir / "err";
  std::string command =
      std::string(RANGEFILL_CLI) + " " + arguments + " >" + out.string() + " 2>" + err.string();
  if (memory_kb > 0) command = "ulimit -v " + std::to_string(memory_kb) + "; " + command;
  const int status = std::system(("/bin/sh -c '" + command + "'").c_str());
  Outcome result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.out = slurp(out);
  result.err = slurp(err);
  fs::remove_all(dir);
  return result;
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string binary_ply_header(const std::string& vertex_count) {
  return "ply\nformat binary_little_endian 1.0\nelement vertex " + vertex_count +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
         "property list uchar int vertex_indices\nend_header\n";
}

std::string triangle_body(float nan_or_zero = 0) {
  const float coordinates[9] = {nan_or_zero, 0, 0, 1, 0, 0, 0, 1, 0};
  std::string body(reinterpret_cast<const char*>(coordinates), sizeof coordinates);
  body += '\3';
  for (int index : {0, 1, 2}) body.append(reinterpret_cast<const char*>(&index), 4);
  return body;
}

TEST(Cli, InfoAndHolesDescribeAMesh) {
  const fs::path dir = testing::temporary_directory("cli-info");
  Mesh grid = testing::make_grid(6);
  grid.triangles.erase(grid.triangles.begin() + 2 * (3 * 6 + 3),
                       grid.triangles.begin() + 2 * (3 * 6 + 3) + 2);
  grid.face_hole.resize(grid.triangles.size());
  write_mesh(grid, dir / "grid.ply");

  const Outcome info = run("info " + (dir / "grid.ply").string());
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("vertices             49"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("boundary loops       2 (edges: "), std::string::npos) << info.out;

  const Outcome holes = run("holes --json " + (dir / "grid.ply").string());
  ASSERT_EQ(holes.exit_code, 0) << holes.err;
  const nlohmann::json json = nlohmann::json::parse(holes.out);
  ASSERT_EQ(json["loops"].size(), 2u);
  int outer = 0;
  for (const auto& loop : json["loops"]) {
    if (loop["longest_in_component"]) {
      ++outer;
      EXPECT_EQ(loop["edges"], 24);
    } else {
      EXPECT_EQ(loop["edges"], 4);
      EXPECT_DOUBLE_EQ(loop["area"].get<double>(), 1.0);
    }
  }
  EXPECT_EQ(outer, 1);
  fs::remove_all(dir);
}

TEST(Cli, UsageErrorsExitWithTwo) {
  EXPECT_EQ(run("").exit_code, 2);
  EXPECT_EQ(run("info").exit_code, 2);
  EXPECT_EQ(run("frobnicate x.ply").exit_code, 2);
  EXPECT_EQ(run("repair a.ply -o b.ply --inpainter nonsense").exit_code, 2);
  EXPECT_EQ(run("info --help").exit_code, 0);
}

TEST(Cli, BadFilesExitWithThreeAndAOneLineMessageNamingTheFile) {
  const fs::path dir = testing::temporary_directory("cli-bad");
  const std::string header = binary_ply_header("3");
  const std::string body = triangle_body();
  std::string out_of_range = header + body;
  out_of_range[out_of_range.size() - 4] = 7;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"empty.ply", ""},
      {"truncated.ply", header + body.substr(0, 20)},
      {"index.ply", out_of_range},
      {"nan.ply", header + triangle_body(std::numeric_limits<float>::quiet_NaN())},
      {"huge.ply", binary_ply_header("1099511627776") + body},
      {"missing.ply", "-"},
  };
  for (const auto& [name, bytes] : cases) {
    SCOPED_TRACE(name);
    const fs::path path = dir / name;
    if (bytes != "-") write_bytes(path, bytes);
    // 2 GB of address space: a reader allocating from the declared 2^40 vertices would fail.
    const Outcome result = run("info " + path.string(), RANGEFILL_SANITIZED ? 0 : 2'000'000);
    EXPECT_EQ(result.exit_code, 3) << result.err;
    EXPECT_NE(result.err.find(path.string()), std::string::npos) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  }
  fs::remove_all(dir);
}

TEST(Cli, RepairClosesASphereCapAndReportsJson) {
  const fs::path dir = testing::temporary_directory("cli-repair");
  const Mesh capless =
      testing::remove_faces(testing::make_sphere(12), [](const Vec3& p) { return p.z() > 0.85; });
  write_mesh(capless, dir / "in.ply");
  const std::string before = slurp(dir / "in.ply");

  const Outcome repair =
      run("repair " + (dir / "in.ply").string() + " -o " + (dir / "out.obj").string() +
          " --fill-all --report " + (dir / "report.json").string());
  ASSERT_EQ(repair.exit_code, 0) << repair.err;
  EXPECT_EQ(slurp(dir / "in.ply"), before);  // the input is untouched
  const Mesh out = read_mesh(dir / "out.obj").mesh;
  EXPECT_TRUE(check_manifold(out).closed_manifold());
  const nlohmann::json report = nlohmann::json::parse(slurp(dir / "report.json"));
  ASSERT_EQ(report["holes"].size(), 1u);
  EXPECT_TRUE(report["holes"][0]["filled"].get<bool>());
  EXPECT_EQ(report["holes"][0]["new_vertices"].get<int>() + capless.vertex_count(),
            out.vertex_count());

  // Without --in-place the input is not overwritten; with the default policy the only loop of a
  // component is its border and stays open.
  EXPECT_EQ(
      run("repair " + (dir / "in.ply").string() + " -o " + (dir / "in.ply").string()).exit_code, 2);
  EXPECT_EQ(slurp(dir / "in.ply"), before);
  const Outcome border =
      run("repair " + (dir / "in.ply").string() + " -o " + (dir / "same.ply").string());
  EXPECT_EQ(border.exit_code, 0) << border.err;
  EXPECT_NE(border.err.find("--fill-all"), std::string::npos);
  EXPECT_EQ(read_mesh(dir / "same.ply").mesh.face_count(), capless.face_count());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rangefill
