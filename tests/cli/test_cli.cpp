// The rangefill binary as a user runs it: exit codes, one-line errors, outputs.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <zlib.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "rangefill/depth/fill_depth.h"
#include "rangefill/eval/metrics.h"
#include "rangefill/eval/punch.h"
#include "rangefill/hole/holes.h"
#include "rangefill/io/depth_io.h"
#include "rangefill/io/mesh_io.h"
#include "rangefill/repair/pipeline.h"
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
  const long first = 2L * (3 * 6 + 3);  // the two triangles of quad (3, 3)
  grid.triangles.erase(grid.triangles.begin() + first, grid.triangles.begin() + first + 2);
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
    if (loop["border"]) {
      ++outer;
      EXPECT_EQ(loop["edges"], 24);
    } else {
      EXPECT_EQ(loop["edges"], 4);
      EXPECT_DOUBLE_EQ(loop["area"].get<double>(), 1.0);
    }
  }
  EXPECT_EQ(outer, 1);
  EXPECT_NE(info.out.find("watertight           no"), std::string::npos) << info.out;

  // A closed cube is watertight; a second cube through it makes the pair of them cut each other.
  Mesh cubes = testing::make_cube();
  write_mesh(cubes, dir / "cube.ply");
  const Outcome cube = run("info " + (dir / "cube.ply").string());
  EXPECT_NE(cube.out.find("self-intersections   0 face pairs"), std::string::npos) << cube.out;
  EXPECT_NE(cube.out.find("watertight           yes"), std::string::npos) << cube.out;
  const Mesh second = testing::make_cube();
  for (const Vec3& p : second.positions) cubes.positions.push_back(p + Vec3(0.5, 0.25, 0.25));
  for (const Triangle& t : second.triangles)
    cubes.triangles.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
  write_mesh(make_mesh(cubes.positions, cubes.triangles), dir / "cubes.ply");
  const Outcome crossing = run("info --json " + (dir / "cubes.ply").string());
  const nlohmann::json crossing_json = nlohmann::json::parse(crossing.out);
  EXPECT_GT(crossing_json["self_intersecting_face_pairs"].get<int>(), 0);
  EXPECT_FALSE(crossing_json["watertight"].get<bool>());
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
      // Files whose content is not what their name says, or no mesh at all.
      {"text.obj", "hello world\nthis is text, not a mesh\n"},
      {"text.ply", "hello world\n"},
      {"no-vertices.off", "OFF\n0 0 0\n"},
      {"no-facets.stl", "solid x\nendsolid x\n"},
  };
  for (const auto& [name, bytes] : cases) {
    SCOPED_TRACE(name);
    const fs::path path = dir / name;
    if (bytes != "-") write_bytes(path, bytes);
    // 2 GB of address space: a reader allocating from the declared 2^40 vertices would fail.
    for (const std::string& command : {"info " + path.string(), "repair " + path.string() + " -o " +
                                                                    (dir / "out.ply").string()}) {
      const Outcome result = run(command, RANGEFILL_SANITIZED ? 0 : 2'000'000);
      EXPECT_EQ(result.exit_code, 3) << result.err;
      EXPECT_NE(result.err.find(path.string()), std::string::npos) << result.err;
      EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    }
  }
  EXPECT_FALSE(fs::exists(dir / "out.ply"));
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

  // Without --in-place the input is not overwritten. The cap is 7.5 % of the sphere, a hole: the
  // default fills it as --fill-all does, and as the library's defaults do, bit for bit.
  EXPECT_EQ(
      run("repair " + (dir / "in.ply").string() + " -o " + (dir / "in.ply").string()).exit_code, 2);
  EXPECT_EQ(slurp(dir / "in.ply"), before);
  const Outcome plain =
      run("repair " + (dir / "in.ply").string() + " -o " + (dir / "plain.ply").string());
  EXPECT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(slurp(dir / "plain.ply"),
            serialize_mesh(rangefill::repair(capless).mesh, MeshFormat::ply));
  EXPECT_EQ(read_mesh(dir / "plain.ply").mesh.triangles, out.triangles);

  // A hemisphere's loop would be filled by half its surface: a border, left open and said so.
  const Mesh hemisphere =
      testing::remove_faces(testing::make_sphere(12), [](const Vec3& p) { return p.z() > -0.01; });
  write_mesh(hemisphere, dir / "half.ply");
  const Outcome border =
      run("repair " + (dir / "half.ply").string() + " -o " + (dir / "same.ply").string());
  EXPECT_EQ(border.exit_code, 0) << border.err;
  EXPECT_NE(border.err.find("--fill-all"), std::string::npos) << border.err;
  EXPECT_NE(border.out.find("1 loops, 0 closed, 1 left open (1 border, "), std::string::npos)
      << border.out;
  EXPECT_EQ(read_mesh(dir / "same.ply").mesh.triangles, hemisphere.triangles);
  fs::remove_all(dir);
}

// A file of coloured points without faces is meshed (greedy projection) and repaired; with
// --mesher none it is refused, naming the file.
TEST(Cli, RepairMeshesAPointCloudFirst) {
  const fs::path dir = testing::temporary_directory("cli-cloud");
  Mesh cloud = testing::make_sphere_cloud(1500, 0.85);
  for (const Vec3& p : cloud.positions) cloud.colors.push_back(Rgb(0.5 + 0.5 * p.x(), 0.3f, 0.7f));
  write_mesh(cloud, dir / "cloud.ply");

  const Outcome repair = run("repair " + (dir / "cloud.ply").string() + " -o " +
                             (dir / "out.ply").string() + " --fill-all --inpainter mls");
  ASSERT_EQ(repair.exit_code, 0) << repair.err;
  EXPECT_NE(repair.err.find("meshed " + std::to_string(cloud.vertex_count()) + " points"),
            std::string::npos)
      << repair.err;
  const Mesh out = read_mesh(dir / "out.ply").mesh;
  EXPECT_TRUE(check_manifold(out).closed_manifold());
  ASSERT_EQ(out.colors.size(), out.positions.size());
  testing::expect_bit_identical(
      {out.positions.begin(), out.positions.begin() + cloud.vertex_count()}, cloud.positions);

  const Outcome refused = run("repair " + (dir / "cloud.ply").string() + " -o " +
                              (dir / "none.ply").string() + " --mesher none");
  EXPECT_EQ(refused.exit_code, 3);
  EXPECT_NE(refused.err.find("cloud.ply"), std::string::npos) << refused.err;
  EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
  EXPECT_FALSE(fs::exists(dir / "none.ply"));
  fs::remove_all(dir);
}

// A 16-bit depth image: a plane at 1.5 m with a 9x9 hole at (row, col).
cv::Mat depth_with_hole(int row, int col) {
  cv::Mat depth(48, 64, CV_16U, cv::Scalar(1500));
  depth(cv::Rect(col, row, 9, 9)).setTo(0);
  return depth;
}

// `rangefill depth IN -o OUT` fills 16-bit PNG and float TIFF/EXR, with a back-end or --fast,
// refuses to write over its input, and names the file in one-line errors: a mask of another size,
// an unreadable image.
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

  // --fast fills along lines instead of a back-end; the JSON report times the fill alone.
  const Outcome fast = run("depth --fast --json " + (dir / "in.png").string() + " -o " +
                           (dir / "fast.png").string());
  ASSERT_EQ(fast.exit_code, 0) << fast.err;
  const nlohmann::json fast_report = nlohmann::json::parse(fast.out);
  EXPECT_EQ(fast_report["filled_pixels"].get<int>(), 81);
  EXPECT_LE(fast_report["fill_seconds"].get<double>(), fast_report["seconds"].get<double>());
  EXPECT_EQ(cv::countNonZero(read_depth_image(dir / "fast.png") != 1500), 0);
  EXPECT_EQ(run("depth --fast --inpainter ns " + (dir / "in.png").string() + " -o " +
                (dir / "f.png").string())
                .exit_code,
            2);

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

// --color takes a JPEG or PNG colour image of the depth's size, and gives fill_depth's bytes with
// it; one of another size is refused naming both files; --batch finds each frame's colour image
// by its stem in --color-dir and skips a frame without one.
TEST(Cli, DepthTakesAColourImage) {
  const fs::path dir = testing::temporary_directory("cli-depth-colour");
  cv::Mat depth(48, 64, CV_16U, cv::Scalar(2000));
  depth.colRange(0, 30).setTo(1940);  // a picture on the wall, one surface for depth alone
  cv::Mat colour(48, 64, CV_8UC3, cv::Scalar(200, 200, 200));
  colour.colRange(0, 30).setTo(cv::Scalar(40, 60, 160));
  cv::circle(depth, {30, 24}, 8, cv::Scalar(0), cv::FILLED);
  write_depth_image(depth, dir / "in.png");
  ASSERT_TRUE(cv::imwrite((dir / "in.jpg").string(), colour, {cv::IMWRITE_JPEG_QUALITY, 100}));
  // Colour guides the fill along lines, which this small hole gets with --inpainter lines.
  const Outcome guided = run("depth --inpainter lines " + (dir / "in.png").string() + " --color " +
                             (dir / "in.jpg").string() + " -o " + (dir / "out.png").string());
  ASSERT_EQ(guided.exit_code, 0) << guided.err;
  DepthFillOptions options;
  options.inpainter = kAlongLines;
  options.color = read_color_image(dir / "in.jpg");
  cv::Mat expected;
  fill_depth(depth, cv::noArray(), expected, options);
  EXPECT_EQ(cv::norm(read_depth_image(dir / "out.png"), expected, cv::NORM_INF), 0);
  cv::Mat plain;
  options.color = cv::Mat();
  fill_depth(depth, cv::noArray(), plain, options);
  EXPECT_GT(cv::norm(plain, expected, cv::NORM_INF), 0);

  ASSERT_TRUE(cv::imwrite((dir / "small.png").string(), colour.colRange(0, 32)));
  const Outcome small = run("depth " + (dir / "in.png").string() + " --color " +
                            (dir / "small.png").string() + " -o " + (dir / "s.png").string());
  EXPECT_EQ(small.exit_code, 3);
  EXPECT_EQ(small.err, "rangefill: " + (dir / "in.png").string() + " and colour " +
                           (dir / "small.png").string() +
                           ": fill_depth: the colour image is 32x48 but the depth is 64x48\n");
  EXPECT_FALSE(fs::exists(dir / "s.png"));

  fs::create_directories(dir / "frames");
  fs::create_directories(dir / "colour");
  write_depth_image(depth, dir / "frames" / "a.png");
  write_depth_image(depth, dir / "frames" / "b.png");
  fs::copy_file(dir / "in.jpg", dir / "colour" / "a.jpg");
  const Outcome batch =
      run("depth --inpainter lines --batch " + (dir / "frames").string() + " --out-dir " +
          (dir / "out").string() + " --color-dir " + (dir / "colour").string());
  EXPECT_EQ(batch.exit_code, 5) << batch.err;
  EXPECT_EQ(cv::norm(read_depth_image(dir / "out" / "a.png"), expected, cv::NORM_INF), 0);
  EXPECT_FALSE(fs::exists(dir / "out" / "b.png"));
  EXPECT_NE(batch.err.find("b.png: no colour image"), std::string::npos) << batch.err;
  fs::remove_all(dir);
}

// Holes on the image border are filled by default; --keep-border leaves them and the summary and
// --json count them; --filled-mask writes exactly the pixels filled.
TEST(Cli, DepthSaysWhatIsLeftAndWritesTheFilledMask) {
  const fs::path dir = testing::temporary_directory("cli-depth-left");
  cv::Mat depth = depth_with_hole(10, 20);
  depth(cv::Rect(0, 30, 4, 5)).setTo(0);  // 20 pixels on the border
  write_depth_image(depth, dir / "in.png");
  const std::string fill =
      "depth " + (dir / "in.png").string() + " -o " + (dir / "out.png").string();
  const Outcome all = run(fill + " --json --filled-mask " + (dir / "filled.png").string());
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const nlohmann::json stats = nlohmann::json::parse(all.out);
  EXPECT_EQ(stats["filled_pixels"], 101);
  EXPECT_EQ(stats["left_pixels"], 0);
  EXPECT_EQ(cv::countNonZero(read_depth_image(dir / "out.png") != 1500), 0);
  const cv::Mat filled = cv::imread((dir / "filled.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(filled.type(), CV_8UC1);
  EXPECT_EQ(cv::norm(filled, depth == 0, cv::NORM_INF), 0);

  const Outcome kept = run(fill + " --keep-border");
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  EXPECT_NE(kept.out.find("2 holes, 1 filled (81 pixels, 0 beside a depth edge); left: 1 holes, "
                          "20 pixels (at the border 1 / 20)"),
            std::string::npos)
      << kept.out;
  const Outcome kept_json = run(fill + " --keep-border --json");
  EXPECT_EQ(nlohmann::json::parse(kept_json.out)["left"]["at_border"],
            (nlohmann::json{{"holes", 1}, {"pixels", 20}}));

  EXPECT_EQ(run(fill + " --filled-mask " + (dir / "in.png").string()).exit_code, 2);
  EXPECT_EQ(run(fill + " --filled-mask " + (dir / "out.png").string()).exit_code, 2);
  write_bytes(dir / "empty.png", "");
  const Outcome empty =
      run("depth " + (dir / "empty.png").string() + " -o " + (dir / "e.png").string());
  EXPECT_EQ(empty.exit_code, 3);
  EXPECT_EQ(empty.err, "rangefill: " + (dir / "empty.png").string() + ": file is empty\n");
  fs::remove_all(dir);
}

// A PNG whose header declares 30000×30000 16-bit pixels over 2×2 pixels of data (OpenCV alone
// would reserve the declared 1.8 GB before finding the data missing, and libpng print its own
// line to stderr): it is refused with exit 3 and one line naming it, also with the address space
// capped at 2 GB.
TEST(Cli, DepthImageDeclaringHugeDimensionsIsRefused) {
  const fs::path dir = testing::temporary_directory("cli-depth-huge");
  std::vector<uchar> png;
  cv::imencode(".png", cv::Mat(2, 2, CV_16U, cv::Scalar(1000)), png);
  std::string bytes(png.begin(), png.end());
  // IHDR: width and height (big endian) at bytes 16–23, its CRC at 29–32.
  for (int k = 0; k < 2; ++k) {
    const unsigned value = 30000;
    for (int b = 0; b < 4; ++b) bytes[16 + 4 * k + b] = static_cast<char>(value >> (24 - 8 * b));
  }
  const unsigned crc =
      static_cast<unsigned>(::crc32(0, reinterpret_cast<const Bytef*>(bytes.data() + 12), 17));
  for (int b = 0; b < 4; ++b) bytes[29 + b] = static_cast<char>(crc >> (24 - 8 * b));
  write_bytes(dir / "huge.png", bytes);
  for (const long cap : {0L, RANGEFILL_SANITIZED ? 0L : 2'000'000L}) {
    const Outcome result =
        run("depth " + (dir / "huge.png").string() + " -o " + (dir / "out.png").string(), cap);
    EXPECT_EQ(result.exit_code, 3) << result.err;
    EXPECT_EQ(result.err, "rangefill: " + (dir / "huge.png").string() +
                              ": corrupt PNG: image data shorter than the header declares\n");
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
  }
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

  // --mask-dir: each frame's mask by its name; a frame without one is skipped and said.
  fs::create_directories(dir / "masks");
  for (int i = 0; i < 4; ++i) {
    cv::Mat mask = cv::Mat::zeros(48, 64, CV_8U);
    mask(cv::Rect(10 + 7 * i, 5 + 5 * i, 3, 3)).setTo(255);  // 9 pixels of the frame's hole
    cv::imwrite((dir / "masks" / ("frame-" + std::to_string(i) + ".png")).string(), mask);
  }
  const Outcome masked = run(batch + (dir / "masked").string() + " --mask-dir " +
                             (dir / "masks").string() + " --json");
  EXPECT_EQ(masked.exit_code, 5);
  int with_mask = 0;
  for (const auto& frame : nlohmann::json::parse(masked.out)) {
    if (!frame["written"].get<bool>()) continue;
    ++with_mask;
    EXPECT_EQ(frame["filled_pixels"], 9) << frame;
  }
  EXPECT_EQ(with_mask, 4);
  EXPECT_NE(masked.err.find("frame-4.png: no mask"), std::string::npos) << masked.err;

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

// `rangefill bench` scores fills against the surface punched out of a closed mesh: an open sheet is
// refused with the reason, before any work.
TEST(Cli, BenchRefusesAMeshThatIsNotClosed) {
  const fs::path dir = testing::temporary_directory("cli-bench-open");
  write_mesh(testing::make_grid(8), dir / "sheet.ply");
  const Outcome bench =
      run("bench --meshes " + (dir / "sheet.ply").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(bench.exit_code, 3);
  EXPECT_NE(bench.err.find("sheet.ply: not a closed 2-manifold (1 boundary loops"),
            std::string::npos)
      << bench.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "holes.csv"));
  fs::remove_all(dir);
}

// Writes a sphere into `dir` and returns the bench command the bench tests share: three holes
// punched into it, two back-ends on planes and `baselines`.
std::string sphere_bench(const fs::path& dir, const std::string& baselines) {
  write_mesh(testing::make_sphere(16), dir / "sphere.ply");
  return "bench --meshes " + (dir / "sphere.ply").string() +
         " --holes-per-mesh 3 --seed 4 --max-radius 6 --inpainters harmonic,ns --filler plane "
         "--baselines " +
         baselines;
}

// `rangefill bench` on a sphere with two back-ends (on planes) and a baseline, each hole and method
// in a process of its own: the summary as JSON; in --out a CSV row per hole and method, the
// summary, the tables, three plots and the report with each hole's images; the same numbers at one
// and two threads; a timeout fails every method on every hole, and the run still ends with its
// tables.
TEST(Cli, BenchComparesMethodsAndWritesItsReport) {
  const fs::path dir = testing::temporary_directory("cli-bench");
  const std::string common = sphere_bench(dir, "cgal-triangulate") + " --json";
  const Outcome one = run(common + " --out " + (dir / "one").string());
  ASSERT_EQ(one.exit_code, 0) << one.err;
  nlohmann::json summary = nlohmann::json::parse(one.out);
  EXPECT_EQ(summary["method_order"],
            (std::vector<std::string>{"harmonic", "ns", "cgal-triangulate"}));
  EXPECT_EQ(summary["holes"].size(), 3u);
  for (const std::string method : {"harmonic", "ns", "cgal-triangulate"}) {
    EXPECT_EQ(summary["methods"][method]["filled"], 3) << method;
    EXPECT_LT(summary["methods"][method]["hausdorff_max"], 2) << method;
    double shares = 0;
    for (double share : summary["methods"][method]["rank_shares"]) shares += share;
    EXPECT_NEAR(shares, 1, 1e-12) << method;
  }
  EXPECT_GT(summary["methods"]["cgal-triangulate"]["edge_ratio_sd"], 0);
  // The statistics: each median inside its bootstrap interval; the best median's method, tested
  // against every other on the same holes (itself: no pair); the holes every back-end filled
  // alike, counted and marked.
  std::string best;
  for (const std::string method : {"harmonic", "ns", "cgal-triangulate"}) {
    const nlohmann::json& figures = summary["methods"][method];
    EXPECT_LE(figures["hausdorff_median_ci95"][0], figures["hausdorff_median"]) << method;
    EXPECT_GE(figures["hausdorff_median_ci95"][1], figures["hausdorff_median"]) << method;
    EXPECT_EQ(figures["versus_best"]["test"], "Wilcoxon signed-rank, two-sided");
    if (best.empty() ||
        figures["hausdorff_median"] < summary["methods"][best]["hausdorff_median"].get<double>()) {
      best = method;
    }
  }
  EXPECT_EQ(summary["best"], best);
  EXPECT_EQ(summary["methods"][best]["versus_best"]["pairs"], 0);
  EXPECT_TRUE(summary["methods"][best]["versus_best"]["p"].is_null());
  int alike = 0;
  for (const nlohmann::json& hole : summary["holes"])
    alike += hole["alike_for_every_backend"].get<bool>();
  EXPECT_EQ(summary["holes_alike_for_every_backend"], alike);
  EXPECT_EQ(summary["backends_among_themselves"]["holes"], 3 - alike);
  const std::string csv = slurp(dir / "one" / "holes.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 3 * 3);
  EXPECT_NE(slurp(dir / "one" / "tables.md").find("(Table 3)"), std::string::npos);
  EXPECT_NE(slurp(dir / "one" / "tables.md").find("The back-ends ranked among themselves"),
            std::string::npos);
  const std::string html = slurp(dir / "one" / "report.html");
  EXPECT_NE(html.find("<svg"), std::string::npos);
  size_t images = 0;
  for (size_t at = html.find("data:image/png;base64,"); at != std::string::npos;
       at = html.find("data:image/png;base64,", at + 1)) {
    ++images;
  }
  EXPECT_EQ(images, 3u * 5u);  // per hole: range image, mask, two restorations, a difference
  for (const char* plot : {"hausdorff-vs-area.svg", "ranks-by-area.svg", "ranks-by-curvature.svg"})
    EXPECT_EQ(slurp(dir / "one" / plot).rfind("<svg", 0), 0u) << plot;

  const Outcome two = run(common + " --threads 2");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  nlohmann::json again = nlohmann::json::parse(two.out);
  for (nlohmann::json* document : {&summary, &again}) {
    for (auto& [method, figures] : (*document)["methods"].items())
      figures.erase("seconds_per_hole_median");
  }
  EXPECT_EQ(summary, again);

  const Outcome late = run(common + " --timeout 0.000001 --csv " + (dir / "late.csv").string());
  ASSERT_EQ(late.exit_code, 0) << late.err;
  EXPECT_EQ(nlohmann::json::parse(late.out)["methods"]["ns"]["filled"], 0);
  EXPECT_NE(slurp(dir / "late.csv").find("timed out after 1e-06 s"), std::string::npos);
  EXPECT_EQ(run(common + " --baselines meshlab").exit_code, 2);
  EXPECT_EQ(run(common + " --shapes square").exit_code, 2);
  fs::remove_all(dir);
}

// The fields of one CSV line (quoted fields may hold commas and doubled quotes).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '"' && quoted && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (line[i] == '"') {
      quoted = !quoted;
    } else if (line[i] == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += line[i];
    }
  }
  return fields;
}

// holes.csv without the columns of times (their names end in "seconds", "_s").
std::vector<std::vector<std::string>> csv_without_times(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(csv);
  std::vector<bool> time_column;
  for (std::string line; std::getline(lines, line);) {
    const std::vector<std::string> fields = csv_fields(line);
    if (time_column.empty()) {
      for (const std::string& name : fields) {
        time_column.push_back(name == "seconds" ||
                              (name.size() > 2 && name.compare(name.size() - 2, 2, "_s") == 0));
      }
    }
    rows.emplace_back();
    for (size_t k = 0; k < fields.size(); ++k) {
      if (!time_column.at(k)) rows.back().push_back(fields[k]);
    }
  }
  return rows;
}

// report.html in headless Chromium (Debian's chromium, with WebGL in software): the page reports
// in its body's data attributes how many holes it drew in 3D (a view that drew nothing or failed
// is not counted), how many depth images it coloured and how many errors it met (a console error,
// an uncaught exception or a rejected promise); Chromium's log has no uncaught error either.
TEST(Cli, BenchReportOpensInABrowserWithA3DViewPerHole) {
  if (std::system("command -v chromium >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "chromium is not installed (scripts/install-deps.sh installs it)";
  }
  const fs::path dir = testing::temporary_directory("cli-bench-browser");
  const Outcome bench = run(sphere_bench(dir, "cgal-fair") + " --out " + (dir / "out").string());
  ASSERT_EQ(bench.exit_code, 0) << bench.err;
  const std::string browser =
      "chromium --headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader "
      "--enable-logging=stderr --v=0 --virtual-time-budget=15000 --user-data-dir=" +
      (dir / "profile").string() + " --dump-dom file://" + (dir / "out" / "report.html").string() +
      " >" + (dir / "dom.html").string() + " 2>" + (dir / "log.txt").string();
  ASSERT_EQ(std::system(browser.c_str()), 0) << slurp(dir / "log.txt");
  const std::string dom = slurp(dir / "dom.html"), log = slurp(dir / "log.txt");
  const size_t body = dom.find("<body");
  ASSERT_NE(body, std::string::npos) << log;
  const std::string tag = dom.substr(body, dom.find('>', body) - body);
  EXPECT_NE(tag.find("data-views=\"3\""), std::string::npos) << tag;
  // Per hole: the range image, its mask, two restorations and the second's difference.
  EXPECT_NE(tag.find("data-images=\"15\""), std::string::npos) << tag;
  EXPECT_EQ(tag.find("data-errors"), std::string::npos) << tag << "\n" << log;
  EXPECT_EQ(log.find("Uncaught"), std::string::npos) << log;
  fs::remove_all(dir);
}

// `rangefill bench --shard K/N` runs a share of the (hole, method) jobs; `--merge` of the shards
// gives the unsharded run's holes.csv (times aside) and summary, and refuses a missing shard, a
// shard given twice and a shard of another run.
TEST(Cli, BenchShardsMergeIntoTheUnshardedRun) {
  const fs::path dir = testing::temporary_directory("cli-bench-shards");
  const std::string common = sphere_bench(dir, "cgal-triangulate");
  const Outcome whole = run(common + " --json --out " + (dir / "whole").string());
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  for (const char* shard : {"0/2", "1/2"}) {
    const std::string out = (dir / ("shard" + std::string(1, shard[0]))).string();
    const Outcome part = run(common + (std::string(" --shard ") + shard) + (" --out " + out));
    ASSERT_EQ(part.exit_code, 0) << part.err;
  }
  const nlohmann::json shard0 = nlohmann::json::parse(slurp(dir / "shard0" / "shard-0-of-2.json"));
  std::vector<std::string> jobs;
  for (const auto& [job, entry] : shard0["runs"].items()) jobs.push_back(job);
  EXPECT_EQ(jobs, (std::vector<std::string>{"0", "2", "4", "6", "8"}));
  const Outcome merged =
      run("bench --merge " + (dir / "shard0").string() + " " + (dir / "shard1").string() +
          " --json --out " + (dir / "merged").string());
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  const auto rows = csv_without_times(slurp(dir / "merged" / "holes.csv"));
  EXPECT_EQ(rows.size(), 1u + 3 * 3);
  EXPECT_EQ(rows, csv_without_times(slurp(dir / "whole" / "holes.csv")));
  nlohmann::json merged_summary = nlohmann::json::parse(merged.out);
  nlohmann::json whole_summary = nlohmann::json::parse(whole.out);
  for (nlohmann::json* document : {&merged_summary, &whole_summary}) {
    for (auto& [method, figures] : (*document)["methods"].items())
      figures.erase("seconds_per_hole_median");
  }
  EXPECT_EQ(merged_summary, whole_summary);
  EXPECT_NE(slurp(dir / "merged" / "summary.json").find("(merged from 2 shards)"),
            std::string::npos);

  const Outcome missing =
      run("bench --merge " + (dir / "shard0").string() + " --out " + (dir / "m1").string());
  EXPECT_EQ(missing.exit_code, 3);
  EXPECT_NE(missing.err.find("shards 1 of 2 are missing"), std::string::npos) << missing.err;
  const Outcome twice = run("bench --merge " + (dir / "shard0").string() + " " +
                            (dir / "shard0").string() + " --out " + (dir / "m2").string());
  EXPECT_EQ(twice.exit_code, 3);
  EXPECT_NE(twice.err.find("shard 0 again"), std::string::npos) << twice.err;
  const std::string other_seed = common.substr(0, common.find("--seed 4")) + "--seed 5" +
                                 common.substr(common.find("--seed 4") + 8);
  ASSERT_EQ(run(other_seed + " --shard 1/2 --out " + (dir / "other").string()).exit_code, 0);
  const Outcome mixed = run("bench --merge " + (dir / "shard0").string() + " " +
                            (dir / "other").string() + " --out " + (dir / "m3").string());
  EXPECT_EQ(mixed.exit_code, 3);
  EXPECT_NE(mixed.err.find("from another bench run"), std::string::npos) << mixed.err;
  EXPECT_EQ(run(common + " --shard 2/2 --out " + (dir / "bad").string()).exit_code, 2);
  EXPECT_EQ(run(common + " --shard 0/2").exit_code, 2);  // no --out
  fs::remove_all(dir);
}

// Writes the holes `punched` of `original` into `dir` as the mesh kit's punch does: holed.ply,
// gt_hole_<id>.ply (the removed faces of hole id) and holes.json with d_m `mean_edge`.
void write_kit_punch(const Mesh& original, const PunchResult& punched, double mean_edge,
                     const fs::path& dir) {
  fs::create_directories(dir);
  write_mesh(punched.mesh, dir / "holed.ply");
  nlohmann::json holes = nlohmann::json::array();
  for (size_t h = 0; h < punched.holes.size(); ++h) {
    const PunchedHole& hole = punched.holes[h];
    write_mesh(extract_faces(original, hole.removed_faces),
               dir / ("gt_hole_" + std::to_string(h) + ".ply"));
    holes.push_back({{"id", h},
                     {"elongated", hole.shape == HoleShape::elongated},
                     {"radius", hole.radius},
                     {"curvature", hole.bending},
                     {"curvature_class", curvature_name(hole.curvature)},
                     {"on_feature", hole.sharp_feature}});
  }
  write_bytes(
      dir / "holes.json",
      nlohmann::json{{"d_m", mean_edge}, {"holed_mesh", "holed.ply"}, {"holes", holes}}.dump());
}

// `rangefill bench --punched DIR` scores the holes another tool punched (the mesh kit's layout):
// written from the very holes `bench --meshes` punches, they get the same distances, hole for hole
// and method for method; a holes.json that is not the kit's is refused, naming it.
TEST(Cli, BenchScoresTheHolesOfTheMeshKitsPunch) {
  const fs::path dir = testing::temporary_directory("cli-bench-punched");
  const std::string common = sphere_bench(dir, "cgal-fair");
  const std::string methods = common.substr(common.find(" --inpainters"));
  const Mesh sphere = read_mesh(dir / "sphere.ply").mesh;
  PunchOptions options;  // as sphere_bench punches it
  options.holes = 3;
  options.seed = seed_for_mesh(4, "sphere.ply");
  options.max_radius = 6;
  options.spread = true;
  options.shapes = {HoleShape::disk, HoleShape::elongated};
  const PunchResult punched = punch_holes(sphere, options);
  ASSERT_EQ(punched.holes.size(), 3u);
  write_kit_punch(sphere, punched, mean_edge_length(sphere), dir / "kit" / "case" / "punch");

  ASSERT_EQ(run(common + " --csv " + (dir / "own.csv").string()).exit_code, 0);
  const Outcome kit = run("bench --punched " + (dir / "kit").string() + methods + " --csv " +
                          (dir / "kit.csv").string());
  ASSERT_EQ(kit.exit_code, 0) << kit.err;
  EXPECT_NE(kit.out.find("1 meshes, 3 holes (punched by the mesh kit)"), std::string::npos)
      << kit.out;
  const auto own_rows = csv_without_times(slurp(dir / "own.csv"));
  const auto kit_rows = csv_without_times(slurp(dir / "kit.csv"));
  ASSERT_EQ(kit_rows.size(), 1u + 3 * 3);
  ASSERT_EQ(kit_rows.size(), own_rows.size());
  const std::vector<std::string>& header = own_rows[0];
  for (const std::string column :
       {"method", "hole", "filled", "hausdorff_dm", "mean_distance_dm", "new_faces", "curvature"}) {
    const size_t k = std::find(header.begin(), header.end(), column) - header.begin();
    ASSERT_LT(k, header.size()) << column;
    for (size_t row = 1; row < own_rows.size(); ++row) {
      EXPECT_EQ(kit_rows[row][k], own_rows[row][k]) << column << ", row " << row;
    }
  }
  EXPECT_EQ(kit_rows[1][0], "case");  // named by the directory above punch/

  write_bytes(dir / "kit" / "case" / "punch" / "holes.json", "{\"holes\": []}");
  const Outcome bad = run("bench --punched " + (dir / "kit").string() + methods);
  EXPECT_EQ(bad.exit_code, 3);
  EXPECT_NE(bad.err.find("holes.json: not a holes.json of the mesh kit's punch"), std::string::npos)
      << bad.err;
  EXPECT_EQ(run("bench --punched " + (dir / "sphere.ply").string() + methods).exit_code, 2);
  EXPECT_EQ(run(common + " --punched " + (dir / "kit").string()).exit_code, 2);
  fs::remove_all(dir);
}

// `rangefill repair --batch DIR --out-dir DIR --shard K/N`: the shards split the directory's
// meshes in name order, each output the bytes of the file's own repair; a file that cannot be
// read is skipped and said (exit 5) while the others are written; the input directory is refused
// as the output.
TEST(Cli, RepairBatchShardsADirectory) {
  const fs::path dir = testing::temporary_directory("cli-repair-batch");
  fs::create_directories(dir / "in");
  const Mesh holed =
      testing::remove_faces(testing::make_sphere(12), [](const Vec3& p) { return p.z() > 0.93; });
  for (const char* name : {"a.ply", "b.obj", "c.ply"}) write_mesh(holed, dir / "in" / name);
  {
    std::ofstream bad(dir / "in" / "d.ply");
    bad << "ply\nformat binary_little_endian 1.0\nelement vertex 3\n";
  }
  const std::string batch =
      "repair --batch " + (dir / "in").string() + " --out-dir " + (dir / "out").string();
  const Outcome first = run(batch + " --shard 0/2");
  EXPECT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out.find("2 files (shard 0/2 of 4), 2 written"), std::string::npos) << first.out;
  EXPECT_TRUE(fs::exists(dir / "out" / "a.ply") && fs::exists(dir / "out" / "c.ply"));
  EXPECT_FALSE(fs::exists(dir / "out" / "b.obj"));
  const Outcome second = run(batch + " --shard 1/2");
  EXPECT_EQ(second.exit_code, 5);
  EXPECT_NE(second.err.find("rangefill: skipped " + (dir / "in" / "d.ply").string()),
            std::string::npos)
      << second.err;
  ASSERT_TRUE(fs::exists(dir / "out" / "b.obj"));
  EXPECT_FALSE(fs::exists(dir / "out" / "d.ply"));
  for (const char* name : {"a.ply", "b.obj"}) {
    const fs::path single = dir / (std::string("single-") + name);
    ASSERT_EQ(run("repair " + (dir / "in" / name).string() + " -o " + single.string()).exit_code,
              0);
    EXPECT_EQ(slurp(dir / "out" / name), slurp(single)) << name;
    EXPECT_EQ(check_manifold(read_mesh(dir / "out" / name).mesh).boundary_loops, 0) << name;
  }
  EXPECT_EQ(run("repair --batch " + (dir / "in").string() + " --out-dir " + (dir / "in").string())
                .exit_code,
            2);
  EXPECT_EQ(run(batch + " " + (dir / "in" / "a.ply").string()).exit_code, 2);
  fs::remove_all(dir);
}

// A sheet with a small and a large hole: `rangefill repair` leaves the border open and says so,
// leaves loops over --max-hole-size open and says so, fills exactly --holes, refuses a loop that
// does not exist (exit 3), and with --fill-all reports the border it cannot fill (a flat sheet's
// border: any fill would lie on the sheet) while the holes are repaired, exit 5.
TEST(Cli, RepairChoosesItsLoopsAndSaysWhichItLeftOpen) {
  const fs::path dir = testing::temporary_directory("cli-open");
  const Mesh sheet = testing::remove_faces(testing::make_grid(30), [](const Vec3& p) {
    return (p - Vec3(8, 15, 0)).norm() < 3 || (p - Vec3(20, 15, 0)).norm() < 6;
  });
  write_mesh(sheet, dir / "sheet.ply");
  int border = -1, small = -1, large = -1;
  for (const BoundaryLoop& loop : find_holes(sheet, build_topology(sheet)).loops) {
    (is_border(loop) ? border : loop.vertices.size() < 30 ? small : large) = loop.id;
  }
  ASSERT_TRUE(border >= 0 && small >= 0 && large >= 0);
  const std::string repair = "repair " + (dir / "sheet.ply").string() + " -o ";
  auto loops_of = [&](const std::string& name) {
    return check_manifold(read_mesh(dir / name).mesh).boundary_loops;
  };
  const std::string border_note =
      "rangefill: note: left open as the border of an open surface (a fill would cover at least "
      "20 % of its component): loop " +
      std::to_string(border) + " (";

  const Outcome plain = run(repair + (dir / "plain.ply").string());
  EXPECT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.err.find(border_note), std::string::npos) << plain.err;
  EXPECT_NE(plain.out.find("3 loops, 2 closed, 1 left open (1 border, 0 over a size limit, 0 "
                           "failed)"),
            std::string::npos)
      << plain.out;
  EXPECT_EQ(loops_of("plain.ply"), 1);

  const int small_edges =
      static_cast<int>(find_holes(sheet, build_topology(sheet)).loops[small].vertices.size());
  const Outcome limited = run(repair + (dir / "limited.ply").string() + " --max-hole-size " +
                              std::to_string(small_edges));
  EXPECT_EQ(limited.exit_code, 0) << limited.err;
  EXPECT_NE(limited.out.find("3 loops, 1 closed, 2 left open (1 border, 1 over a size limit, 0 "
                             "failed)"),
            std::string::npos)
      << limited.out;
  EXPECT_EQ(loops_of("limited.ply"), 2);

  const Outcome named =
      run(repair + (dir / "named.ply").string() + " --holes " + std::to_string(large) + " --json");
  EXPECT_EQ(named.exit_code, 0) << named.err;
  const nlohmann::json named_report = nlohmann::json::parse(named.out);
  EXPECT_EQ(named_report["holes"].size(), 1u);
  EXPECT_EQ(loops_of("named.ply"), 2);
  // Each loop of the output, with the loop of the input it is and why it is open.
  EXPECT_EQ(named_report["loops_left_open"], 2);
  std::map<int, std::string> reasons;
  for (const auto& loop : named_report["open_loops"]) {
    reasons[loop["hole"].get<int>()] = loop["reason"].get<std::string>();
  }
  EXPECT_EQ(reasons,
            (std::map<int, std::string>{{border, "not selected"}, {small, "not selected"}}));

  const Outcome missing = run(repair + (dir / "missing.ply").string() + " --holes 7");
  EXPECT_EQ(missing.exit_code, 3);
  EXPECT_EQ(missing.err, "rangefill: " + (dir / "sheet.ply").string() +
                             ": repair: there is no boundary loop 7 to fill (the mesh has 3)\n");
  EXPECT_FALSE(fs::exists(dir / "missing.ply"));

  const Outcome all = run(repair + (dir / "all.ply").string() + " --fill-all --report " +
                          (dir / "all.json").string());
  EXPECT_EQ(all.exit_code, 5) << all.err;
  EXPECT_NE(all.err.find("partial repair, loops left open that were to be filled: 1"),
            std::string::npos)
      << all.err;
  EXPECT_EQ(loops_of("all.ply"), 1);  // the holes are filled all the same
  const nlohmann::json report = nlohmann::json::parse(slurp(dir / "all.json"));
  int refused = 0;
  for (const auto& hole : report["holes"]) {
    if (hole["filled"].get<bool>()) continue;
    ++refused;
    EXPECT_EQ(hole["id"].get<int>(), border);
    EXPECT_NE(hole["failure"].get<std::string>().find("hole " + std::to_string(border) + ": "),
              std::string::npos);
  }
  EXPECT_EQ(refused, 1);

  // The report may not be written over the input or the output.
  EXPECT_EQ(run(repair + (dir / "r.ply").string() + " --report " + (dir / "sheet.ply").string())
                .exit_code,
            2);
  fs::remove_all(dir);
}

// Ctrl-C during `rangefill repair` leaves no temporary file, and the output is either absent or
// complete, byte for byte what an uninterrupted run writes; the interrupted run exits with 130.
// SIGINT is sent once while the mesh is repaired and once while the output is being written (as
// soon as the process holds a file of the output directory open).
TEST(Cli, InterruptedRepairLeavesNoTemporaryOrPartialFile) {
  const fs::path dir = testing::temporary_directory("cli-interrupt");
  const Mesh capless =
      testing::remove_faces(testing::make_sphere(90), [](const Vec3& p) { return p.z() > 0.97; });
  write_mesh(capless, dir / "in.ply");
  const fs::path out = dir / "out.ply";
  const std::vector<std::string> arguments = {
      RANGEFILL_CLI, "repair", (dir / "in.ply").string(), "-o", out.string(),
      "--fill-all",  "--ascii"};
  auto spawn = [&] {
    std::vector<char*> argv;
    for (const std::string& argument : arguments)
      argv.push_back(const_cast<char*>(argument.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = 0;
    EXPECT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
    posix_spawn_file_actions_destroy(&actions);
    return pid;
  };
  auto exit_code = [](pid_t pid) {
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  };
  // Whether the process has ended (it is not reaped: exit_code still can be).
  auto exited = [](pid_t pid) {
    siginfo_t info{};
    return ::waitid(P_PID, pid, &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid;
  };
  // Whether the process holds open a file of `dir` other than the input: the output being written.
  auto writing = [&](pid_t pid) {
    std::error_code error;
    for (const fs::directory_entry& fd :
         fs::directory_iterator("/proc/" + std::to_string(pid) + "/fd", error)) {
      const fs::path target = fs::read_symlink(fd.path(), error);
      if (!error && target.parent_path() == dir && target.filename() != "in.ply") return true;
    }
    return false;
  };
  auto expect_clean = [&](const std::string& complete) {
    for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
    }
    EXPECT_TRUE(!fs::exists(out) || slurp(out) == complete) << "a partial output";
  };

  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(exit_code(spawn()), 0);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string complete = slurp(out);
  ASSERT_FALSE(complete.empty());

  fs::remove(out);
  const pid_t repairing = spawn();
  ASSERT_GT(repairing, 0);  // else kill() would signal our process group, the loop below spin
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds / 3));
  ::kill(repairing, SIGINT);
  EXPECT_EQ(exit_code(repairing), 130);
  expect_clean(complete);
  EXPECT_FALSE(fs::exists(out));

  // The write is caught in the act unless the process finished in between two looks, or the
  // signal came in just after its last write (then it exits 0, its output complete).
  bool interrupted_writing = false;
  for (int attempt = 0; attempt < 5 && !interrupted_writing; ++attempt) {
    fs::remove(out);
    const pid_t pid = spawn();
    ASSERT_GT(pid, 0);
    bool caught = false;
    while (!caught && !exited(pid)) {
      caught = writing(pid);
      if (!caught) std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
    if (caught) ::kill(pid, SIGINT);
    const int code = exit_code(pid);
    EXPECT_TRUE(code == 130 || code == 0) << code;
    interrupted_writing = caught && code == 130;
    expect_clean(complete);
  }
  EXPECT_TRUE(interrupted_writing) << "never interrupted the output being written";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rangefill
