// The rangefill binary as a user runs it: exit codes, one-line errors, outputs.
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rangefill/depth.h"
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

// A 16-bit depth image: a plane at 1.5 m with a 9x9 hole at (row, col).
cv::Mat depth_with_hole(int row, int col) {
  cv::Mat depth(48, 64, CV_16U, cv::Scalar(1500));
  depth(cv::Rect(col, row, 9, 9)).setTo(0);
  return depth;
}

// `rangefill depth IN -o OUT` fills 16-bit PNG and float TIFF/EXR, refuses to write over its input,
// and names the file in one-line errors: a mask of another size, an unreadable image.
TEST(Cli, DepthFillsOneImage) {
  const fs::path dir = testing::temporary_directory("cli-depth");
  write_depth_image(depth_with_hole(10, 20), dir / "in.png");
  const Outcome png =
      run("depth " + (dir / "in.png").string() + " -o " + (dir / "out.png").string());
  ASSERT_EQ(png.exit_code, 0) << png.err;
  EXPECT_NE(png.out.find("1 holes, 1 filled (81 pixels"), std::string::npos) << png.out;
  EXPECT_EQ(cv::countNonZero(read_depth_image(dir / "out.png") != 1500), 0);

  cv::Mat metres;
  depth_with_hole(20, 30).convertTo(metres, CV_32F, 1e-3);
  metres.setTo(std::numeric_limits<float>::quiet_NaN(), metres == 0);
  write_depth_image(metres, dir / "in.tif");
  const Outcome exr = run("depth --json " + (dir / "in.tif").string() + " -o " +
                          (dir / "out.exr").string() + " --inpainter telea");
  ASSERT_EQ(exr.exit_code, 0) << exr.err;
  EXPECT_EQ(nlohmann::json::parse(exr.out)["filled_pixels"].get<int>(), 81);
  const cv::Mat filled = read_depth_image(dir / "out.exr");
  ASSERT_EQ(filled.type(), CV_32FC1);
  EXPECT_LT(cv::norm(filled, cv::Mat(48, 64, CV_32F, cv::Scalar(1.5f)), cv::NORM_INF), 1e-6);

  const std::string before = slurp(dir / "in.png");
  EXPECT_EQ(
      run("depth " + (dir / "in.png").string() + " -o " + (dir / "in.png").string()).exit_code, 2);
  EXPECT_EQ(slurp(dir / "in.png"), before);
  EXPECT_EQ(
      run("depth " + (dir / "in.tif").string() + " -o " + (dir / "out.png").string()).exit_code,
      3);  // PNG cannot hold float depth

  write_depth_image(cv::Mat(10, 10, CV_16U, cv::Scalar(1)), dir / "small.png");
  const Outcome mask = run("depth " + (dir / "in.png").string() + " --mask " +
                           (dir / "small.png").string() + " -o " + (dir / "m.png").string());
  EXPECT_EQ(mask.exit_code, 3);
  EXPECT_EQ(mask.err, "rangefill: " + (dir / "in.png").string() + " with mask " +
                          (dir / "small.png").string() +
                          ": fill_depth: mask is 10x10 but depth is 64x48\n");
  write_bytes(dir / "bad.png", "not a PNG");
  const Outcome bad =
      run("depth " + (dir / "bad.png").string() + " -o " + (dir / "b.png").string());
  EXPECT_EQ(bad.exit_code, 3);
  EXPECT_EQ(bad.err,
            "rangefill: " + (dir / "bad.png").string() + ": not a PNG, TIFF or EXR image\n");
  EXPECT_FALSE(fs::exists(dir / "b.png"));
  fs::remove_all(dir);
}

// `rangefill depth --batch`: every image of the directory, the same bytes at any thread count,
// unreadable files skipped and reported (exit 5), shards that partition the files, and never the
// input directory as output.
TEST(Cli, DepthBatchFillsADirectory) {
  const fs::path dir = testing::temporary_directory("cli-depth-batch");
  fs::create_directories(dir / "in");
  for (int i = 0; i < 5; ++i) {
    write_depth_image(depth_with_hole(5 + 5 * i, 10 + 7 * i),
                      dir / "in" / ("frame-" + std::to_string(i) + ".png"));
  }
  write_bytes(dir / "in" / "broken.png", "not a PNG");
  write_bytes(dir / "in" / "notes.txt", "not an image, not looked at");

  const std::string batch = "depth --batch " + (dir / "in").string() + " --out-dir ";
  const Outcome one = run(batch + (dir / "one").string());
  EXPECT_EQ(one.exit_code, 5);
  EXPECT_NE(one.err.find("rangefill: skipped " + (dir / "in" / "broken.png").string() +
                         ": not a PNG, TIFF or EXR image"),
            std::string::npos)
      << one.err;
  EXPECT_NE(one.out.find("6 files (shard 0/1 of 6), 5 written"), std::string::npos) << one.out;
  const Outcome two = run(batch + (dir / "two").string() + " --threads 2");
  EXPECT_EQ(two.exit_code, 5);
  for (int i = 0; i < 5; ++i) {
    const std::string name = "frame-" + std::to_string(i) + ".png";
    EXPECT_EQ(cv::countNonZero(read_depth_image(dir / "one" / name) != 1500), 0) << name;
    EXPECT_EQ(slurp(dir / "one" / name), slurp(dir / "two" / name)) << name;
  }

  // Shards 0/2 and 1/2 of the six files (broken.png first): three each, none twice.
  EXPECT_EQ(run(batch + (dir / "shards").string() + " --shard 0/2").exit_code, 5);
  EXPECT_EQ(run(batch + (dir / "shards").string() + " --shard 1/2").exit_code, 0);
  int written = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir / "shards")) ++written;
  EXPECT_EQ(written, 5);

  EXPECT_EQ(run(batch + (dir / "in").string()).exit_code, 2);
  EXPECT_EQ(run(batch + (dir / "x").string() + " --shard 2/2").exit_code, 2);
  EXPECT_EQ(run(batch + (dir / "x").string() + " -o y.png").exit_code, 2);
  fs::remove_all(dir);
}

// `rangefill depth-bench` on a rendered sphere with one back-end prints its table.
TEST(Cli, DepthBenchMeasuresABackEnd) {
  const fs::path dir = testing::temporary_directory("cli-depth-bench");
  write_mesh(testing::make_sphere(8), dir / "sphere.ply");
  const Outcome bench = run("depth-bench --meshes " + (dir / "sphere.ply").string() +
                            " --views 1 --patterns 1 --inpainters harmonic");
  ASSERT_EQ(bench.exit_code, 0) << bench.err;
  EXPECT_NE(bench.out.find("rendered frames: 1"), std::string::npos) << bench.out;
  EXPECT_NE(bench.out.find("fill_depth harmonic"), std::string::npos) << bench.out;
  EXPECT_NE(bench.out.find("cv::inpaint telea, all invalid masked"), std::string::npos);
  EXPECT_EQ(run("depth-bench --inpainters harmonic").exit_code, 2);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rangefill
