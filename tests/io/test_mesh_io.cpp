// OBJ, OFF and STL reading and writing (PLY has its own test file).
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <sys/stat.h>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "rangefill/io/mesh_io.h"
#include "support.h"

namespace rangefill {
namespace {

namespace fs = std::filesystem;

// The cube with coordinates that need every bit of a double (0.1, 1/3, ...), float64 storage.
Mesh awkward_cube() {
  Mesh mesh = testing::make_cube();
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    mesh.positions[v] = mesh.positions[v] / 3.0 + Vec3(0.1, -1e-7 * v, 12345.678901234567);
  }
  mesh.storage.position = ScalarType::float64;
  return mesh;
}

// The cube with coordinates exactly representable as floats, float32 storage.
Mesh float_cube() {
  Mesh mesh = testing::make_cube();
  for (Vec3& p : mesh.positions) p = testing::round_to_float(p / 3.0 + Vec3(0.1, -2.5, 1e3));
  mesh.storage.position = ScalarType::float32;
  return mesh;
}

void add_float_normals(Mesh& mesh) {
  mesh.normals = vertex_normals_from_faces(mesh);
  mesh.storage.normal = ScalarType::float64;
}

// Colours with components 0 and 1 (written "0.0"/"1.0" in OFF) and others that need a float.
void add_float_colours(Mesh& mesh) {
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    mesh.colors.emplace_back(v % 2, 0.1f * static_cast<float>(v), 1.0f / 3.0f);
  }
  mesh.storage.color = ScalarType::float32;
}

void add_eight_bit_colours(Mesh& mesh) {
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    mesh.colors.push_back((Eigen::Vector3d(255, 30 * v, 7) * (1.0 / 255.0)).cast<float>());
  }
  mesh.storage.color = ScalarType::uint8;
}

// Vertex order, faces, and the attributes the mesh has, all exactly.
void expect_same_mesh(const Mesh& actual, const Mesh& expected) {
  testing::expect_bit_identical(actual.positions, expected.positions);
  EXPECT_EQ(actual.triangles, expected.triangles);
  testing::expect_bit_identical(actual.normals, expected.normals);
  EXPECT_EQ(actual.colors, expected.colors);
  EXPECT_EQ(actual.vertex_hole, std::vector<int>(expected.vertex_count(), kOriginal));
  EXPECT_EQ(actual.face_hole, std::vector<int>(expected.face_count(), kOriginal));
}

ReadResult round_trip(const Mesh& mesh, MeshFormat format, const WriteOptions& options = {}) {
  return parse_mesh(serialize_mesh(mesh, format, options), format, "memory");
}

ReadResult round_trip_through_file(const Mesh& mesh, const std::string& file_name,
                                   const WriteOptions& options = {}) {
  const fs::path dir = testing::temporary_directory("io");
  write_mesh(mesh, dir / file_name, options);
  ReadResult result = read_mesh(dir / file_name);
  fs::remove_all(dir);
  return result;
}

ReadResult parse(const std::string& bytes, MeshFormat format) {
  return parse_mesh(bytes, format, "test");
}

// The message of the InvalidInput that parsing throws; checks it is one line naming the file.
std::string error_of(const std::string& bytes, MeshFormat format) {
  const std::string name = "input/bad-file";
  try {
    parse_mesh(bytes, format, name);
  } catch (const InvalidInput& error) {
    std::string message = error.what();
    EXPECT_EQ(message.rfind(name + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  }
  ADD_FAILURE() << "no InvalidInput for: " << bytes.substr(0, 200);
  return {};
}

#define EXPECT_CONTAINS(text, fragment) \
  EXPECT_NE(std::string(text).find(fragment), std::string::npos) << (text)

// Corner positions of every triangle, for formats that renumber vertices (STL).
void expect_same_triangle_corners(const Mesh& actual, const Mesh& expected) {
  ASSERT_EQ(actual.face_count(), expected.face_count());
  for (int f = 0; f < expected.face_count(); ++f) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(actual.positions[actual.triangles[f][k]],
                expected.positions[expected.triangles[f][k]])
          << "face " << f << " corner " << k;
    }
  }
}

double signed_area_z(const Mesh& mesh, int face) {
  return triangle_cross(mesh, face).z() / 2;
}

// A file of megabytes goes out in pieces as it is made: in every format and encoding it holds the
// bytes serialize_mesh gives; read back through its own pages, it is the mesh again.
TEST(MeshIo, LargeFilesAreWrittenInPiecesWithTheSameBytes) {
  const Mesh mesh = testing::make_grid(300);  // 180 000 faces: megabytes a file
  WriteOptions ascii;
  ascii.encoding = Encoding::ascii;
  const fs::path dir = testing::temporary_directory("io-large");
  for (const auto& [name, options] :
       {std::pair{"grid.ply", WriteOptions{}}, std::pair{"grid-ascii.ply", ascii},
        std::pair{"grid.obj", WriteOptions{}}, std::pair{"grid.off", WriteOptions{}},
        std::pair{"grid.stl", WriteOptions{}}, std::pair{"grid-ascii.stl", ascii}}) {
    write_mesh(mesh, dir / name, options);
    const std::string written = read_file(dir / name);
    EXPECT_GT(written.size(), 2u << 20) << name;
    EXPECT_TRUE(written == serialize_mesh(mesh, format_from_extension(dir / name), options))
        << name;
  }
  expect_same_mesh(read_mesh(dir / "grid.ply").mesh, mesh);
  fs::remove_all(dir);
}

// A mesh from a pipe (no size to read ahead) is read to its end.
TEST(MeshIo, ReadsAMeshFromAPipe) {
  const Mesh mesh = testing::make_grid(40);
  const fs::path dir = testing::temporary_directory("io-pipe");
  const fs::path pipe = dir / "mesh.off";
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  std::thread writer(
      [&] { std::ofstream(pipe, std::ios::binary) << serialize_mesh(mesh, MeshFormat::off); });
  const ReadResult read = read_mesh(pipe);
  writer.join();
  EXPECT_EQ(read.mesh.triangles, mesh.triangles);
  EXPECT_EQ(read.mesh.vertex_count(), mesh.vertex_count());
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// OBJ

TEST(ObjIo, RoundTripKeepsVertexOrderFacesColoursAndNormalsBitExact) {
  Mesh mesh = awkward_cube();
  add_float_normals(mesh);
  add_float_colours(mesh);
  for (const ReadResult& back :
       {round_trip(mesh, MeshFormat::obj), round_trip_through_file(mesh, "cube.obj")}) {
    expect_same_mesh(back.mesh, mesh);
    EXPECT_EQ(back.mesh.storage.position, ScalarType::float64);
    EXPECT_TRUE(back.warnings.empty()) << back.warnings.front();
  }
}

TEST(ObjIo, EightBitColoursComeBackAsEightBit) {
  Mesh mesh = testing::make_cube();
  add_eight_bit_colours(mesh);
  const ReadResult back = round_trip(mesh, MeshFormat::obj);
  EXPECT_EQ(back.mesh.colors, mesh.colors);
  EXPECT_EQ(back.mesh.storage.color, ScalarType::uint8);
}

TEST(ObjIo, WritesHeaderVerticesAndFaces) {
  Mesh mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  EXPECT_EQ(serialize_mesh(mesh, MeshFormat::obj),
            "# written by rangefill\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  mesh.normals.assign(3, Vec3(0, 0, 1));
  EXPECT_CONTAINS(serialize_mesh(mesh, MeshFormat::obj),
                  "vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nf 1//1 2//2 3//3\n");
}

TEST(ObjIo, ReadsNumbersCorrectlyRoundedUpToTheLargestDouble) {
  // Not 0.70000000000000007 for 0.7, nor inf for the largest double.
  const ReadResult result =
      parse("v 0.7 0.3333333333333333 1.7976931348623157e308\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            MeshFormat::obj);
  EXPECT_EQ(result.mesh.positions[0], Vec3(0.7, 1.0 / 3.0, 1.7976931348623157e308));
}

TEST(ObjIo, KeepsFaceOrderAcrossObjectsGroupsAndMaterials) {
  const ReadResult result = parse(
      "# comment\nmtllib a.mtl\no first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf -3 -2 -1\n"
      "g second\nv 1 1 0\nusemtl blue\nf 2 4 3\nusemtl red\nf 1 4 3\ng third\nf 1 2 4\n",
      MeshFormat::obj);
  EXPECT_EQ(result.mesh.triangles,
            (std::vector<Triangle>{{0, 1, 2}, {1, 3, 2}, {0, 3, 2}, {0, 1, 3}}));
  EXPECT_EQ(result.warnings,
            std::vector<std::string>{"test: 3 material assignments (usemtl) dropped"});
}

TEST(ObjIo, NegativeIndicesCountBackFromTheLastVertexAndNormalReadSoFar) {
  const ReadResult result = parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf -3//-1 -2//-1 -1//-1\n"
      "v 1 1 0\nvn 0 0 -1\nf -3//1 -1//1 -2//-2\n",
      MeshFormat::obj);
  EXPECT_EQ(result.mesh.triangles, (std::vector<Triangle>{{0, 1, 2}, {1, 3, 2}}));
  ASSERT_TRUE(result.mesh.has_normals());
  EXPECT_EQ(result.mesh.normals[3], Vec3(0, 0, 1));
  EXPECT_TRUE(result.warnings.empty()) << result.warnings.front();
}

TEST(ObjIo, PositiveIndicesMayReferToVerticesDefinedLater) {
  const ReadResult result = parse("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", MeshFormat::obj);
  EXPECT_EQ(result.mesh.triangles, (std::vector<Triangle>{{0, 1, 2}}));
}

TEST(ObjIo, AcceptsCommentsAfterFacesAndCrlfLineEnds) {
  const ReadResult result =
      parse("v 0 0 0\r\nv 1 0 0 # x\r\nv 0 1 0\r\nf 1 2 3 # comment\r\n", MeshFormat::obj);
  EXPECT_EQ(result.mesh.triangles, (std::vector<Triangle>{{0, 1, 2}}));
  EXPECT_EQ(result.mesh.positions[1], Vec3(1, 0, 0));
  EXPECT_TRUE(result.warnings.empty()) << result.warnings.front();
}

TEST(ObjIo, QuadIsTriangulatedWithAWarning) {
  const ReadResult result =
      parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", MeshFormat::obj);
  ASSERT_EQ(result.mesh.face_count(), 2);
  EXPECT_NEAR(signed_area_z(result.mesh, 0) + signed_area_z(result.mesh, 1), 1.0, 1e-12);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_CONTAINS(result.warnings[0], "triangulated");
}

TEST(ObjIo, PolygonWithMoreThan255CornersIsRead) {
  // 300 corners: more than one byte can count.
  constexpr double kPi = 3.14159265358979323846;
  std::string text;
  const int corners = 300;
  for (int k = 0; k < corners; ++k) {
    const double angle = 2 * kPi * k / corners;
    text += "v " + std::to_string(std::cos(angle)) + " " + std::to_string(std::sin(angle)) + " 0\n";
  }
  text += "f";
  for (int k = 1; k <= corners; ++k) text += " " + std::to_string(k);
  text += "\nf 1 2 3\n";
  const ReadResult result = parse(text, MeshFormat::obj);
  EXPECT_EQ(result.mesh.face_count(), corners - 2 + 1);
  EXPECT_EQ(result.mesh.triangles.back(), (Triangle{0, 1, 2}));
}

TEST(ObjIo, NormalsPairedConsistentlyBecomePerVertexNormals) {
  const ReadResult result =
      parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nvn 0 0 1\nvn 0 0.6 0.8\nf 1//2 2//1 3//1\n",
            MeshFormat::obj);
  ASSERT_TRUE(result.mesh.has_normals());
  EXPECT_EQ(result.mesh.normals[0], Vec3(0, 0.6, 0.8));
  EXPECT_EQ(result.mesh.normals[1], Vec3(0, 0, 1));
  EXPECT_EQ(result.mesh.normals[3], Vec3::Zero());  // in no face
  EXPECT_TRUE(result.warnings.empty());
}

TEST(ObjIo, NormalsAreDroppedWithAWarningWhenAVertexHasTwo) {
  const ReadResult result = parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 0 -1\nf 1//1 2//1 3//1\n"
      "f 2//2 4//2 3//2\n",
      MeshFormat::obj);
  EXPECT_FALSE(result.mesh.has_normals());
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_CONTAINS(result.warnings[0], "normals dropped");
  EXPECT_CONTAINS(result.warnings[0], "vertex 2 is paired with normals 1 and 2");
}

TEST(ObjIo, NormalsAreDroppedWithAWarningWhenACornerHasNone) {
  const ReadResult result =
      parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2 3//1\n", MeshFormat::obj);
  EXPECT_FALSE(result.mesh.has_normals());
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_CONTAINS(result.warnings[0], "line 5");
}

TEST(ObjIo, ColoursOnSomeVerticesOnlyAreDroppedWithAWarning) {
  const ReadResult result =
      parse("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n", MeshFormat::obj);
  EXPECT_FALSE(result.mesh.has_colors());
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_CONTAINS(result.warnings[0], "only 2 of 3 vertices");
}

TEST(ObjIo, ColoursAbove1AreEightBit) {
  const ReadResult result =
      parse("v 0 0 0 255 0 0\nv 1 0 0 0 128 0\nv 0 1 0 0 0 1\nf 1 2 3\n", MeshFormat::obj);
  ASSERT_TRUE(result.mesh.has_colors());
  EXPECT_EQ(result.mesh.storage.color, ScalarType::uint8);
  EXPECT_EQ(result.mesh.colors[1], Rgb(0, static_cast<float>(128 / 255.0), 0));
}

TEST(ObjIo, DroppedTextureCoordinatesAndLinesAreReported) {
  const ReadResult result = parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\nl 1 2\n", MeshFormat::obj);
  EXPECT_EQ(result.mesh.face_count(), 1);
  ASSERT_EQ(result.warnings.size(), 2u);
  EXPECT_CONTAINS(result.warnings[0], "3 texture coordinates");
  EXPECT_CONTAINS(result.warnings[1], "1 polylines");
}

TEST(ObjIo, MalformedInputThrowsInvalidInputWithOneLineNamingTheFile) {
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  error_of("", MeshFormat::obj);
  EXPECT_CONTAINS(error_of(triangle + "f 1 2 9\n", MeshFormat::obj),
                  "line 4: face refers to vertex 9, outside the file's 3 vertices");
  EXPECT_CONTAINS(error_of(triangle + "f 1 2 -9\n", MeshFormat::obj),
                  "line 4: face refers to a vertex before the first one");
  EXPECT_CONTAINS(error_of("f -1 -2 -3\n" + triangle, MeshFormat::obj),
                  "line 1: face refers to a vertex before the first one");
  EXPECT_CONTAINS(error_of(triangle + "vn 0 0 1\nf 1//1 2//1 3//-2\n", MeshFormat::obj),
                  "line 5: face refers to a normal before the first one");
  // Not wrapped to 1 as atoi would.
  EXPECT_CONTAINS(error_of(triangle + "f 1 2 4294967297\n", MeshFormat::obj), "'4294967297'");
  EXPECT_CONTAINS(error_of(triangle + "f 1 2 0\n", MeshFormat::obj), "line 4");
  EXPECT_CONTAINS(error_of(triangle + "f 1 2 3x\n", MeshFormat::obj), "'3x'");
  EXPECT_CONTAINS(error_of(triangle + "f 1 2\n", MeshFormat::obj), "at least 3");
  EXPECT_CONTAINS(error_of(triangle + "f 1 2 2\n", MeshFormat::obj),
                  "line 4: face repeats vertex 2");
  EXPECT_CONTAINS(error_of(triangle + "f 1 2 -3\n", MeshFormat::obj),
                  "line 4: face repeats vertex 1");
  EXPECT_CONTAINS(error_of(triangle + "f 1/1/1/1 2 3\n", MeshFormat::obj),
                  "'1/1/1/1' is not a vertex reference");
  EXPECT_CONTAINS(error_of(triangle + "f 1// 2 3\n", MeshFormat::obj), "'1//'");
  EXPECT_CONTAINS(error_of(triangle + "f 1//4 2//4 3//4\n", MeshFormat::obj), "normal 4");
  EXPECT_CONTAINS(error_of("v nan 0 0\n" + triangle + "f 2 3 4\n", MeshFormat::obj),
                  "line 1: 'nan' is not a finite number");
  EXPECT_CONTAINS(error_of("v 1e999 0 0\n", MeshFormat::obj), "line 1");
  EXPECT_CONTAINS(error_of(triangle + "v 1 x 3\n", MeshFormat::obj), "line 4: 'x'");
  EXPECT_CONTAINS(error_of(triangle + "v 1 2\n", MeshFormat::obj), "line 4: vertex has 2 values");
  EXPECT_CONTAINS(error_of(triangle + "vn 0 0\n", MeshFormat::obj), "line 4");
  EXPECT_CONTAINS(error_of(triangle + "v 0 0 0 -1 0 0\n", MeshFormat::obj), "outside [0, 255]");
}

// ---------------------------------------------------------------------------------------------
// OFF

TEST(OffIo, RoundTripKeepsVertexOrderAndFacesBitExact) {
  const Mesh mesh = awkward_cube();
  for (const ReadResult& back :
       {round_trip(mesh, MeshFormat::off), round_trip_through_file(mesh, "cube.off")}) {
    expect_same_mesh(back.mesh, mesh);
    EXPECT_TRUE(back.warnings.empty());
  }
  EXPECT_EQ(serialize_mesh(mesh, MeshFormat::off).substr(0, 11), "OFF\n8 12 0\n");
}

TEST(OffIo, NormalsAndColoursRoundTripInEveryKeyword) {
  for (const bool normals : {false, true}) {
    for (const bool eight_bit : {false, true}) {
      Mesh mesh = awkward_cube();
      if (normals) add_float_normals(mesh);
      eight_bit ? add_eight_bit_colours(mesh) : add_float_colours(mesh);
      const std::string text = serialize_mesh(mesh, MeshFormat::off);
      EXPECT_EQ(text.substr(0, text.find('\n')), normals ? "CNOFF" : "COFF");
      for (const ReadResult& back :
           {round_trip(mesh, MeshFormat::off), round_trip_through_file(mesh, "cube.off")}) {
        SCOPED_TRACE(text.substr(0, 200));
        expect_same_mesh(back.mesh, mesh);
        EXPECT_EQ(back.mesh.storage.color, mesh.storage.color);
        EXPECT_TRUE(back.warnings.empty()) << back.warnings.front();
      }
    }
  }
}

TEST(OffIo, NormalsOnlyUseNoff) {
  Mesh mesh = awkward_cube();
  add_float_normals(mesh);
  EXPECT_EQ(serialize_mesh(mesh, MeshFormat::off).substr(0, 5), "NOFF\n");
  expect_same_mesh(round_trip(mesh, MeshFormat::off).mesh, mesh);
}

TEST(OffIo, ColourRuleTellsEightBitFromFloatColours) {
  const std::string faces = "1 0 1 2 3\n";
  // All integers: 8-bit, although none exceeds 1 (with a warning, as that is ambiguous).
  ReadResult result =
      parse("COFF\n3 1 0\n0 0 0 1 0 0\n1 0 0 0 1 0\n0 1 0 0 0 1\n3 0 1 2\n", MeshFormat::off);
  EXPECT_EQ(result.mesh.storage.color, ScalarType::uint8);
  EXPECT_EQ(result.mesh.colors[0], Rgb(static_cast<float>(1 / 255.0), 0, 0));
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_CONTAINS(result.warnings[0], "read as 8-bit");
  // A decimal point makes them floats in [0, 1].
  result =
      parse("COFF\n3 1 0\n0 0 0 1.0 0 0\n1 0 0 0 0.5 0\n0 1 0 0 0 1\n3 0 1 2\n", MeshFormat::off);
  EXPECT_EQ(result.mesh.storage.color, ScalarType::float32);
  EXPECT_EQ(result.mesh.colors[0], Rgb(1, 0, 0));
  EXPECT_EQ(result.mesh.colors[1], Rgb(0, 0.5f, 0));
  EXPECT_TRUE(result.warnings.empty());
  // A component above 1 makes them 8-bit even when written as floats.
  result = parse("COFF\n3 1 0\n0 0 0 255.0 0 0\n1 0 0 0 127.5 0\n0 1 0 0 0 1\n3 0 1 2\n",
                 MeshFormat::off);
  EXPECT_EQ(result.mesh.storage.color, ScalarType::float32);  // 127.5 is no 8-bit value
  EXPECT_EQ(result.mesh.colors[0], Rgb(1, 0, 0));
  EXPECT_FLOAT_EQ(result.mesh.colors[1].y(), 0.5f);
}

TEST(OffIo, AlphaAndFaceColoursAreKeptAsPropertiesAndWrittenBack) {
  const std::string text =
      "COFF\n3 1 0\n0 0 0 255 0 0 10\n1 0 0 0 255 0 20\n0 1 0 0 0 255 30\n3 0 1 2 9 8 7\n";
  const ReadResult result = parse(text, MeshFormat::off);
  ASSERT_EQ(result.mesh.vertex_properties.size(), 1u);
  EXPECT_EQ(result.mesh.vertex_properties[0].name, "alpha");
  EXPECT_EQ(result.mesh.vertex_properties[0].type, ScalarType::uint8);
  EXPECT_EQ(result.mesh.vertex_properties[0].values, (std::vector<double>{10, 20, 30}));
  ASSERT_EQ(result.mesh.face_properties.size(), 3u);
  EXPECT_EQ(result.mesh.face_properties[0].name, "red");
  EXPECT_EQ(result.mesh.face_properties[2].values, std::vector<double>{7});
  EXPECT_EQ(serialize_mesh(result.mesh, MeshFormat::off), text);
}

TEST(OffIo, ConcavePentagonIsTriangulatedWithinItsOutline) {
  // Area 10; a fan from the first corner would cover 14.
  const ReadResult result =
      parse("OFF\n5 1 0\n0 0 0\n4 0 0\n4 4 0\n2 1 0\n0 4 0\n5 0 1 2 3 4\n", MeshFormat::off);
  ASSERT_EQ(result.mesh.face_count(), 3);
  double area = 0;
  for (int f = 0; f < 3; ++f) {
    EXPECT_GT(signed_area_z(result.mesh, f), 0) << "face " << f;
    area += signed_area_z(result.mesh, f);
  }
  EXPECT_NEAR(area, 10.0, 1e-12);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_CONTAINS(result.warnings[0], "triangulated");
}

TEST(OffIo, AcceptsCommentsCountsGluedToTheKeywordAndNoKeyword) {
  const std::vector<Triangle> expected = {{0, 1, 2}};
  EXPECT_EQ(parse("# made by hand\nOFF # keyword\n\n3 1 0\n0 0 0\n1 0 0 # x\n0 1 0\n3 0 1 2\n",
                  MeshFormat::off)
                .mesh.triangles,
            expected);
  EXPECT_EQ(parse("OFF3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::off).mesh.triangles,
            expected);
  EXPECT_EQ(parse("3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::off).mesh.triangles,
            expected);
}

TEST(OffIo, HugeDeclaredCountsFailFastWithoutAllocating) {
  const auto start = std::chrono::steady_clock::now();
  const std::string message =
      error_of("OFF\n1099511627776 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::off);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  EXPECT_CONTAINS(message, "1099511627776 vertices");
  EXPECT_CONTAINS(error_of("OFF\n3 1099511627776 0\n0 0 0\n", MeshFormat::off), "faces");
  EXPECT_CONTAINS(
      error_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000000000 0 1 2\n", MeshFormat::off),
      "lists 3");
}

TEST(OffIo, MalformedInputThrowsInvalidInputWithOneLineNamingTheFile) {
  const std::string header = "OFF\n3 1 0\n";
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  error_of("", MeshFormat::off);
  EXPECT_CONTAINS(error_of("# only a comment\n", MeshFormat::off), "empty");
  EXPECT_CONTAINS(error_of(header + vertices + "3 0 1 3\n", MeshFormat::off),
                  "line 6: face 0 refers to vertex 3, out of range [0, 3)");
  EXPECT_CONTAINS(error_of(header + vertices + "3 0 1 -1\n", MeshFormat::off), "line 6");
  EXPECT_CONTAINS(error_of(header + vertices + "3 0 1 1\n", MeshFormat::off), "repeats");
  EXPECT_CONTAINS(error_of(header + "nan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::off),
                  "line 3: 'nan' is not a finite number");
  EXPECT_CONTAINS(error_of(header + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", MeshFormat::off),
                  "line 4: 'x' is not a valid number");
  EXPECT_CONTAINS(error_of(header + vertices + "3 0 1 2.0\n", MeshFormat::off), "'2.0'");
  EXPECT_CONTAINS(error_of(header + "0 0 0\n1 0 0\n", MeshFormat::off), "truncated");
  EXPECT_CONTAINS(error_of(header + vertices + "# long enough for a face\n", MeshFormat::off),
                  "file ends after 0 of the 1 faces");
  EXPECT_CONTAINS(error_of(header + vertices + "3 0 1 2\n3 0 1 2\n", MeshFormat::off),
                  "line 7: unexpected data");
  EXPECT_CONTAINS(error_of(header + "0 0 0 1\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::off),
                  "line 3: vertex 0 has 4 values");
  EXPECT_CONTAINS(error_of(header + vertices + "2 0 1 # padding\n", MeshFormat::off), "at least 3");
  EXPECT_CONTAINS(error_of(header + vertices + "3 0 1 2 5 5\n", MeshFormat::off),
                  "2 values after its vertex indices");
  EXPECT_CONTAINS(
      error_of("COFF\n3 1 0\n0 0 0 300 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n", MeshFormat::off),
      "outside [0, 255]");
  EXPECT_CONTAINS(error_of("OFF BINARY\n", MeshFormat::off), "binary OFF is not supported");
  EXPECT_CONTAINS(error_of("STOFF\n3 1 0\n", MeshFormat::off), "not supported");
  EXPECT_CONTAINS(error_of("PLY\n3 1 0\n", MeshFormat::off), "not an OFF file");
  EXPECT_CONTAINS(error_of("OFF\n3 1\n", MeshFormat::off), "truncated");
  EXPECT_CONTAINS(error_of("OFF\n-3 1 0\n", MeshFormat::off), "negative");
  EXPECT_CONTAINS(error_of("OFF\n3\n", MeshFormat::off), "counts");
}

// ---------------------------------------------------------------------------------------------
// STL

TEST(StlIo, BinaryAndAsciiRoundTripsKeepEveryTriangleExactly) {
  const Mesh mesh = float_cube();
  for (const Encoding encoding : {Encoding::binary, Encoding::ascii}) {
    WriteOptions options;
    options.encoding = encoding;
    for (const ReadResult& back : {round_trip(mesh, MeshFormat::stl, options),
                                   round_trip_through_file(mesh, "cube.stl", options)}) {
      EXPECT_EQ(back.mesh.vertex_count(), mesh.vertex_count());
      expect_same_triangle_corners(back.mesh, mesh);
      EXPECT_EQ(back.mesh.storage.position, ScalarType::float32);
      EXPECT_TRUE(back.warnings.empty()) << back.warnings.front();
    }
  }
}

TEST(StlIo, WeldingNumbersVerticesInOrderOfFirstOccurrence) {
  // A strip whose faces visit the vertices in index order comes back numbered as it was.
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  for (int i = 0; i < 6; ++i)
    positions.emplace_back(static_cast<float>(i / 2) + 0.1f, (i % 2) * 0.75, 0.5);
  for (int i = 0; i < 4; ++i) triangles.push_back({i, i + 1, i + 2});
  const Mesh strip = make_mesh(positions, triangles);
  const ReadResult back = round_trip(strip, MeshFormat::stl);
  testing::expect_bit_identical(back.mesh.positions, strip.positions);
  EXPECT_EQ(back.mesh.triangles, strip.triangles);
}

TEST(StlIo, BinaryLayoutHasANonSolidHeaderAndUnitNormals) {
  const Mesh mesh = make_mesh({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}, {{0, 1, 2}});
  const std::string bytes = serialize_mesh(mesh, MeshFormat::stl);
  ASSERT_EQ(bytes.size(), 84u + 50u);
  EXPECT_EQ(bytes.substr(0, 80), "rangefill" + std::string(71, ' '));
  EXPECT_EQ(bytes.substr(80, 4), std::string("\1\0\0\0", 4));
  float normal[3];
  std::memcpy(normal, bytes.data() + 84, sizeof normal);
  EXPECT_EQ(normal[0], 0.0f);
  EXPECT_EQ(normal[1], 0.0f);
  EXPECT_EQ(normal[2], 1.0f);
  WriteOptions ascii;
  ascii.encoding = Encoding::ascii;
  EXPECT_CONTAINS(serialize_mesh(mesh, MeshFormat::stl, ascii), "facet normal 0 0 1\n");
}

TEST(StlIo, BinaryFileWhoseHeaderStartsWithSolidIsReadAsBinary) {
  std::string bytes = serialize_mesh(float_cube(), MeshFormat::stl);
  bytes.replace(0, 6, "solid ");
  EXPECT_EQ(parse(bytes, MeshFormat::stl).mesh.face_count(), 12);
  bytes.pop_back();  // now truncated: must not be taken for ASCII
  EXPECT_CONTAINS(error_of(bytes, MeshFormat::stl), "declares 12 facets");
}

TEST(StlIo, DegenerateFacetsAreDroppedWithOneWarning) {
  const std::string ascii =
      "solid t\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
      "endfacet\n"
      "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 0 0\nendloop\n"
      "endfacet\n"
      "facet normal 0 0 0\nouter loop\nvertex 5 5 5\nvertex 5 5 5\nvertex 5 5 5\nendloop\n"
      "endfacet\n"
      "endsolid t\n";
  const ReadResult result = parse(ascii, MeshFormat::stl);
  EXPECT_EQ(result.mesh.face_count(), 1);
  EXPECT_EQ(result.mesh.vertex_count(), 3);  // none from the dropped facets
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_CONTAINS(result.warnings[0], "2 degenerate facets");
}

TEST(StlIo, AsciiAcceptsSeveralSolidsAndAnyCase) {
  const std::string facet =
      "  FACET NORMAL 0 0 1\n    OUTER LOOP\n      VERTEX 0 0 0\n      VERTEX 1 0 0\n"
      "      VERTEX 0 1 0\n    ENDLOOP\n  ENDFACET\n";
  const std::string second =
      "facet normal 0 0 1 outer loop vertex 1 0 0 vertex 1 1 0 vertex 0 1 0 endloop endfacet\n";
  const ReadResult result = parse(
      "  SOLID a b\n" + facet + "ENDSOLID a b\nsolid\n" + second + "endsolid\n", MeshFormat::stl);
  EXPECT_EQ(result.mesh.triangles, (std::vector<Triangle>{{0, 1, 2}, {1, 3, 2}}));
  EXPECT_TRUE(result.warnings.empty());
}

TEST(StlIo, MalformedInputThrowsInvalidInputWithOneLineNamingTheFile) {
  EXPECT_CONTAINS(error_of("", MeshFormat::stl), "empty");
  const std::string binary = serialize_mesh(float_cube(), MeshFormat::stl);
  EXPECT_CONTAINS(error_of(binary.substr(0, binary.size() - 20), MeshFormat::stl),
                  "declares 12 facets (684 bytes) but the file has 664 bytes");
  EXPECT_CONTAINS(error_of(binary.substr(0, 50), MeshFormat::stl), "too short");
  EXPECT_CONTAINS(
      error_of("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 x 0\n", MeshFormat::stl),
      "line 4: 'x' is not a valid number");
  EXPECT_CONTAINS(
      error_of("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 nan 0\n", MeshFormat::stl),
      "line 4");
  EXPECT_CONTAINS(
      error_of("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", MeshFormat::stl),
      "file ends where 'vertex' was expected");
  EXPECT_CONTAINS(error_of("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                           "vertex 0 1 0\nendfacet\n",
                           MeshFormat::stl),
                  "line 7: expected 'endloop', found 'endfacet'");
  EXPECT_CONTAINS(error_of("solid x\nfacet normal 0 0 outer loop\n", MeshFormat::stl),
                  "'outer' is not a valid number");
  EXPECT_CONTAINS(error_of("solid x\nendsolid x\njunk\n", MeshFormat::stl),
                  "line 3: expected 'solid'");
}

TEST(StlIo, AsciiFileWithoutEndsolidIsReadWithAWarning) {
  const ReadResult result = parse(
      "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\n",
      MeshFormat::stl);
  EXPECT_EQ(result.mesh.face_count(), 1);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_CONTAINS(result.warnings[0], "endsolid");
}

// ---------------------------------------------------------------------------------------------
// The fuzzers' seed corpus (tests/fuzz/corpus/<format>/, with their findings):
// every file fails with one line naming it, or reads, and then writes and reads back with the
// same counts (as the fuzzers demand). Under RANGEFILL_SANITIZE this replays them with the
// sanitizers.

TEST(FuzzCorpus, EveryFileReadsOrFailsWithOneLineNamingIt) {
  const fs::path corpus = fs::path(RANGEFILL_SOURCE_DIR) / "tests" / "fuzz" / "corpus";
  int files = 0;
  for (const char* format : {"ply", "obj", "off", "stl"}) {
    for (const fs::directory_entry& entry : fs::directory_iterator(corpus / format)) {
      const std::string name = entry.path().filename().string();
      SCOPED_TRACE(name);
      ++files;
      const MeshFormat kind = format_from_extension(std::string("x.") + format);
      Mesh mesh;
      try {
        mesh = parse_mesh(read_file(entry.path()), kind, name).mesh;
      } catch (const InvalidInput& error) {
        const std::string message = error.what();
        EXPECT_EQ(message.rfind(name + ": ", 0), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        continue;
      }
      const Mesh back = parse_mesh(serialize_mesh(mesh, kind), kind, name).mesh;
      EXPECT_EQ(back.vertex_count(), mesh.vertex_count());
      EXPECT_EQ(back.face_count(), mesh.face_count());
    }
  }
  EXPECT_GE(files, 12);
}

}  // namespace
}  // namespace rangefill
