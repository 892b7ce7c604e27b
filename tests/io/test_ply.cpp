#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"
#include "rangefill/io/mesh_io.h"
#include "support.h"

namespace rangefill {
namespace {

// A mesh whose coordinates use every bit of a double (or of a float when `float32`).
Mesh awkward_mesh(bool float32) {
  Mesh mesh = testing::make_cube();
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    Vec3& p = mesh.positions[v];
    p = p * (1.0 / 3.0) + Vec3(0.1, -1e-7 * v, 12345.678901234567);
    if (float32) p = testing::round_to_float(p);
  }
  mesh.storage.position = float32 ? ScalarType::float32 : ScalarType::float64;
  return mesh;
}

Mesh round_trip(const Mesh& mesh, const WriteOptions& options) {
  return parse_mesh(serialize_mesh(mesh, MeshFormat::ply, options), MeshFormat::ply, "mem.ply")
      .mesh;
}

std::string message_of(const std::string& bytes) {
  try {
    parse_mesh(bytes, MeshFormat::ply, "bad.ply");
  } catch (const InvalidInput& error) {
    return error.what();
  }
  return "no error";
}

TEST(PlyIo, BinaryPositionsRoundTripBitExactInBothEndiannessesAndPrecisions) {
  for (bool float32 : {false, true}) {
    for (bool big_endian : {false, true}) {
      SCOPED_TRACE(std::string(float32 ? "float" : "double") + (big_endian ? " big" : " little"));
      const Mesh mesh = awkward_mesh(float32);
      WriteOptions options;
      options.big_endian = big_endian;
      const Mesh back = round_trip(mesh, options);
      testing::expect_bit_identical(back.positions, mesh.positions);
      EXPECT_EQ(back.triangles, mesh.triangles);
      EXPECT_EQ(back.storage.position, mesh.storage.position);
    }
  }
}

TEST(PlyIo, AsciiRoundTripReadsBackTheSameValues) {
  WriteOptions ascii;
  ascii.encoding = Encoding::ascii;
  for (bool float32 : {false, true}) {
    const Mesh mesh = awkward_mesh(float32);
    const std::string text = serialize_mesh(mesh, MeshFormat::ply, ascii);
    EXPECT_NE(text.find("format ascii 1.0"), std::string::npos);
    const Mesh back = round_trip(mesh, ascii);
    testing::expect_bit_identical(back.positions, mesh.positions);  // shortest round-trip printing
    EXPECT_EQ(back.triangles, mesh.triangles);
  }
}

TEST(PlyIo, ColoursNormalsExtraPropertiesAndProvenanceSurvive) {
  Mesh mesh = testing::make_cube();
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    mesh.colors.push_back(Rgb(v * 30, 255 - v * 7, 128) / 255.0f);
    mesh.normals.push_back(testing::round_to_float(mesh.positions[v].normalized()));
  }
  mesh.vertex_properties.push_back({"quality", ScalarType::float32, {}});
  mesh.vertex_properties.push_back({"alpha", ScalarType::uint8, {}});
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    mesh.vertex_properties[0].values.push_back(static_cast<float>(0.1 * v));
    mesh.vertex_properties[1].values.push_back(200 + v);
  }
  mesh.face_properties.push_back({"label", ScalarType::int16, std::vector<double>(12, -3)});
  const int v = add_vertex(mesh, Vec3(0.5, 0.5, 2), 4, Rgb(1, 0, 0), Vec3(0, 0, 1));
  add_face(mesh, {4, 5, v}, 4);

  for (Encoding encoding : {Encoding::binary, Encoding::ascii}) {
    WriteOptions options;
    options.encoding = encoding;
    const Mesh back = round_trip(mesh, options);
    EXPECT_EQ(back.colors, mesh.colors);
    testing::expect_bit_identical(back.normals, mesh.normals);
    ASSERT_EQ(back.vertex_properties.size(), 2u);
    EXPECT_EQ(back.vertex_properties[0].name, "quality");
    EXPECT_EQ(back.vertex_properties[0].values, mesh.vertex_properties[0].values);
    EXPECT_EQ(back.vertex_properties[1].type, ScalarType::uint8);
    EXPECT_EQ(back.vertex_properties[1].values, mesh.vertex_properties[1].values);
    ASSERT_EQ(back.face_properties.size(), 1u);
    EXPECT_EQ(back.face_properties[0].values, mesh.face_properties[0].values);
    EXPECT_EQ(back.vertex_hole, mesh.vertex_hole);
    EXPECT_EQ(back.face_hole, mesh.face_hole);
    EXPECT_EQ(back.triangles, mesh.triangles);
  }
}

TEST(PlyIo, ProvenanceIsOnlyWrittenWhenSomethingWasGenerated) {
  const std::string plain = serialize_mesh(testing::make_cube(), MeshFormat::ply);
  EXPECT_EQ(plain.find("rangefill_hole"), std::string::npos);
  Mesh mesh = testing::make_cube();
  add_face(mesh, {0, 3, 5}, 0);
  EXPECT_NE(serialize_mesh(mesh, MeshFormat::ply).find("rangefill_hole"), std::string::npos);
}

TEST(PlyIo, WriteThenReadFileKeepsFacesInOrder) {
  const auto dir = testing::temporary_directory("ply");
  const Mesh mesh = awkward_mesh(false);
  write_mesh(mesh, dir / "cube.ply");
  const ReadResult back = read_mesh(dir / "cube.ply");
  EXPECT_EQ(back.mesh.triangles, mesh.triangles);
  testing::expect_bit_identical(back.mesh.positions, mesh.positions);
  EXPECT_TRUE(back.warnings.empty());
  // Nothing else (no temporary file) is left in the directory.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
}

TEST(PlyIo, PolygonsAreTriangulatedWithAWarning) {
  const std::string text =
      "ply\r\nformat ascii 1.0\r\ncomment a quad and a triangle\r\nelement vertex 5\r\n"
      "property float x\r\nproperty float y\r\nproperty float z\r\n"
      "element face 2\r\nproperty list uchar int vertex_index\r\nend_header\r\n"
      "0 0 0\r\n1 0 0\r\n1 1 0\r\n0 1 0\r\n2 0 0\r\n4 0 1 2 3\r\n3 1 4 2\r\n";
  const ReadResult result = parse_mesh(text, MeshFormat::ply, "quad.ply");
  EXPECT_EQ(result.mesh.face_count(), 3);
  EXPECT_EQ(result.mesh.triangles[2], (Triangle{1, 4, 2}));
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_NE(result.warnings[0].find("1 polygons"), std::string::npos);
}

TEST(PlyIo, UnknownElementsAndListPropertiesAreSkipped) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nproperty list uchar float weights\nelement face 1\n"
      "property list uchar uint vertex_indices\nproperty list uchar float texcoord\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
      "0 0 0 2 0.5 0.5\n1 0 0 0\n0 1 0 1 7\n3 0 1 2 6 0 0 1 0 0 1\n0 1\n";
  const ReadResult result = parse_mesh(text, MeshFormat::ply, "extra.ply");
  EXPECT_EQ(result.mesh.vertex_count(), 3);
  EXPECT_EQ(result.mesh.triangles, (std::vector<Triangle>{{0, 1, 2}}));
  EXPECT_EQ(result.warnings.size(), 3u);  // weights, texcoord, edge
}

TEST(PlyIo, MalformedFilesGiveOneLineErrors) {
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  std::string body(size_t{3} * 12, '\0');
  const float one = 1.0f;
  std::memcpy(&body[12], &one, 4);
  std::memcpy(&body[28], &one, 4);
  std::string face = "\x03";
  for (int index : {0, 1, 2}) face.append(reinterpret_cast<const char*>(&index), 4);
  ASSERT_EQ(message_of(header + body + face), "no error");

  const std::string empty = message_of("");
  EXPECT_NE(empty.find("bad.ply"), std::string::npos);
  const std::string truncated = message_of(header + body + face.substr(0, 7));
  EXPECT_NE(truncated.find("face 0"), std::string::npos) << truncated;

  std::string out_of_range = face;
  const int nine = 9;
  std::memcpy(&out_of_range[9], &nine, 4);
  EXPECT_EQ(message_of(header + body + out_of_range),
            "bad.ply: face 0 refers to vertex 9, out of range [0, 3)");

  std::string nan_body = body;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan_body[4], &nan, 4);
  EXPECT_EQ(message_of(header + nan_body + face), "bad.ply: vertex 0 has a non-finite coordinate");

  std::string huge = header;
  huge.replace(huge.find("vertex 3"), 8, "vertex 1099511627776");
  const std::string huge_message = message_of(huge + body + face);
  EXPECT_NE(huge_message.find("declares 1099511627776 vertex"), std::string::npos) << huge_message;

  std::string huge_list = face;
  huge_list[0] = '\xff';
  EXPECT_NE(message_of(header + body + huge_list).find("bad.ply: face 0"), std::string::npos);

  EXPECT_NE(message_of("solid x\n").find("not a PLY file"), std::string::npos);
  EXPECT_NE(message_of("ply\nformat ascii 1.0\nelement vertex 1\n").find("end_header"),
            std::string::npos);
  EXPECT_NE(message_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty quux x\nend_header\n")
                .find("unknown property type 'quux'"),
            std::string::npos);
  EXPECT_NE(message_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                       "property float y\nproperty float z\nend_header\n0 zero 0\n")
                .find("vertex 0: expected a number, found 'zero'"),
            std::string::npos);
  // A scalar under the index list's name would be written beside the list, under the same name.
  std::string scalar_indices = header;
  scalar_indices.replace(scalar_indices.find("property list uchar int vertex_indices"), 38,
                         "property list uchar int vertex_index\nproperty int vertex_indices");
  std::string scalar_face = face;
  scalar_face.append(4, '\0');
  EXPECT_EQ(message_of(scalar_indices + body + scalar_face),
            "bad.ply: face property 'vertex_indices' is not an integer list of vertices");
  for (const std::string& message : {empty, truncated, huge_message}) {
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
}

// An ASCII value outside its declared integer type is refused, not cast unchecked (undefined
// behaviour) and written back wrapped; a provenance value must be a hole id.
TEST(PlyIo, AsciiIntegersMustFitTheirDeclaredType) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar quality\nproperty float rangefill_hole\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const std::string face = "3 0 1 2\n";
  auto vertices = [](const std::string& quality, const std::string& hole) {
    return "0 0 0 " + quality + " " + hole + "\n1 0 0 0 -1\n0 1 0 0 -1\n";
  };
  EXPECT_EQ(message_of(header + vertices("255", "-1") + face), "no error");
  EXPECT_EQ(message_of(header + vertices("256", "-1") + face),
            "bad.ply: vertex 0: expected an integer of type uchar, found '256'");
  EXPECT_EQ(message_of(header + vertices("-1", "-1") + face),
            "bad.ply: vertex 0: expected an integer of type uchar, found '-1'");
  EXPECT_EQ(message_of(header + vertices("2.333e26", "-1") + face),
            "bad.ply: vertex 0: expected an integer of type uchar, found '2.333e26'");
  EXPECT_NE(message_of(header + vertices("0", "1e30") + face).find("is not a hole id"),
            std::string::npos);
  EXPECT_NE(message_of(header + vertices("0", "0.5") + face).find("is not a hole id"),
            std::string::npos);
}

// Positions are written back in a type that holds all three coordinates, not in that of x alone:
// a double y or z read with a float x comes back unrounded (and finite); a property declared
// twice does not lose the first.
TEST(PlyIo, MixedTypesAndIncompleteTriplesLoseNothing) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty double y\n"
      "property float z\nproperty float nx\nproperty uchar red\nproperty float green\n"
      "property uchar blue\nelement face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n0 1e300 0 0.5 1 0.5 2\n1 0.1 0 -0.5 3 0.25 4\n0 1 0 1 5 1 6\n3 0 1 2\n";
  const Mesh mesh = parse_mesh(text, MeshFormat::ply, "mixed.ply").mesh;
  EXPECT_EQ(mesh.storage.position, ScalarType::float64);
  EXPECT_EQ(mesh.positions[0].y(), 1e300);
  EXPECT_EQ(mesh.positions[1].y(), 0.1);
  EXPECT_FALSE(mesh.has_normals());  // nx alone, and a colour of mixed types, stay properties
  EXPECT_FALSE(mesh.has_colors());
  ASSERT_EQ(mesh.vertex_properties.size(), 4u);
  for (const Encoding encoding : {Encoding::binary, Encoding::ascii}) {
    WriteOptions options;
    options.encoding = encoding;
    const Mesh back = round_trip(mesh, options);
    testing::expect_bit_identical(back.positions, mesh.positions);
    ASSERT_EQ(back.vertex_properties.size(), mesh.vertex_properties.size());
    for (size_t i = 0; i < mesh.vertex_properties.size(); ++i) {
      EXPECT_EQ(back.vertex_properties[i].name, mesh.vertex_properties[i].name);
      EXPECT_EQ(back.vertex_properties[i].values, mesh.vertex_properties[i].values);
    }
  }
  EXPECT_EQ(message_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                       "property float y\nproperty float x\nend_header\n"),
            "bad.ply: PLY header line 6: property 'x' declared twice in element 'vertex'");
}

TEST(PlyIo, SharedMeshesRoundTripBitExact) {
  RANGEFILL_REQUIRE_SHARED(data);
  for (const char* file : {"meshes/bunny.ply", "real-holes/face.ply"}) {
    const Mesh mesh = read_mesh(data / file).mesh;
    EXPECT_EQ(mesh.storage.position, ScalarType::float32);
    const Mesh back = round_trip(mesh, {});
    testing::expect_bit_identical(back.positions, mesh.positions);
    EXPECT_EQ(back.triangles, mesh.triangles);
  }
}

}  // namespace
}  // namespace rangefill
