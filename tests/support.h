// Helpers shared by the tests: built meshes and access to ../shared.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rangefill/core/mesh.h"
#include "rangefill/hole/fill.h"
#include "rangefill/hole/holes.h"
#include "rangefill/hole/zone.h"
#include "rangefill/image/plane_filler.h"
#include "rangefill/repair/fillers.h"
#include "rangefill/repair/pipeline.h"

namespace rangefill::testing {

/// ../shared/data, or nullopt when it is absent (the caller then GTEST_SKIP()s with a message).
std::optional<std::filesystem::path> shared_data_dir();

/// A fresh empty directory under the system temp directory, unique per call.
std::filesystem::path temporary_directory(const std::string& stem);

/// The float nearest to each coordinate, back in double. Out of line on purpose: GCC 12 at -O2/-O3
/// may vectorise `v.cast<float>().cast<double>()` into a no-op for some components.
Vec3 round_to_float(const Vec3& v);

/// Repair options whose chain is the Pérez pipeline's: planes first, then the advancing front, the
/// parts of a complex hole and the loop's patches. Tests of the image path and of the back-ends
/// use it.
RepairOptions paper_chain(const PlaneFillerOptions& plane = {});

/// The image pipeline's options with back-end `inpainter` and `trend`, the rest defaults.
PlaneFillerOptions plane_options(const std::string& inpainter,
                                 TrendKind trend = TrendKind::automatic);

/// The unit cube [0,1]³ as 12 outward-facing triangles on 8 vertices.
Mesh make_cube();

/// A flat n×n grid of quads (2 triangles each) in z = 0 with spacing 1, counter-clockwise seen from
/// +z.
Mesh make_grid(int n);

/// A unit sphere: the icosahedron with each face split into frequency² triangles, projected onto
/// the sphere (edge length about 1.05 / frequency), outward-facing.
Mesh make_sphere(int frequency);

/// `n` points spread evenly over the unit sphere (the Fibonacci lattice) below z = `cut`, as a
/// mesh without faces: a point cloud sampled from a closed surface, with a cap cut out.
Mesh make_sphere_cloud(int n, double cut);

/// A closed surface of revolution about the z axis, outward-facing: `profile` lists (radius, z)
/// from the bottom pole (radius 0) to the top pole (radius 0); each point between them becomes a
/// ring of `segments` vertices, the poles single vertices.
Mesh make_revolution(const std::vector<Eigen::Vector2d>& profile, int segments);

/// A capsule along z: a cylinder of `radius` from z = −half_length to half_length closed by
/// hemispheres, with edges of about `step` (rings `step` apart along the profile).
Mesh make_capsule(double radius, double half_length, double step);

/// A spinning top: two cones of base radius `rim` and height `height` glued base to base along a
/// circular crease at z = 0, `steps` rings on each cone and `segments` vertices round.
Mesh make_double_cone(double rim, double height, int steps, int segments);

/// The angle of p about the z axis, in degrees in [0, 360).
double azimuth_degrees(const Vec3& p);

/// The unit cube [0,1]³ with every side an n×n grid of make_grid, welded along the sharp edges,
/// outward-facing.
Mesh make_box(int n);

/// Removes the faces whose three vertices satisfy `inside`, keeping every vertex (unreferenced ones
/// included, so that vertex indices stay those of `mesh`).
template <typename Predicate>
Mesh remove_faces(const Mesh& mesh, Predicate inside) {
  std::vector<Triangle> kept;
  for (const Triangle& t : mesh.triangles) {
    if (!(inside(mesh.positions[t[0]]) && inside(mesh.positions[t[1]]) &&
          inside(mesh.positions[t[2]]))) {
      kept.push_back(t);
    }
  }
  return make_mesh(mesh.positions, kept);
}

/// Removes the two triangles of grid quad (x, y) from make_grid(n).
void remove_grid_quad(Mesh& mesh, int n, int x, int y);

/// The loop of `mesh` of least area_share (empty if none): the hole of a sheet with one.
BoundaryLoop inner_loop(const Mesh& mesh);

/// The smallest angle of the fill's triangles (of a loop of `mesh`), in degrees.
double smallest_angle(const Mesh& mesh, const Fill& fill);

/// EXPECTs that the two lists hold the same doubles, bit for bit (which == would not tell of -0).
void expect_bit_identical(const std::vector<Vec3>& actual, const std::vector<Vec3>& expected);

/// EXPECTs that the input's vertices and faces are the first of the output, unchanged, and that
/// every later vertex is marked as generated.
void expect_input_preserved(const Mesh& input, const Mesh& output);

/// make_grid(n) moved by `rotation` and `shift`, with the faces whose three vertices lie within
/// `radius` of `centre` (grid coordinates) removed: an open sheet with one round hole.
struct TiltedSheet {
  Mesh mesh;
  Eigen::Matrix3d rotation;  // grid → world
  Vec3 shift;
  BoundaryLoop hole;  // the round hole, not the sheet's border
  Zone zone;          // every face
  double size = 0;    // bounding-box diagonal, the scale of tolerances
  Vec3 normal() const { return rotation.col(2); }
  double distance(const Vec3& p) const { return std::abs((p - shift).dot(normal())); }
};
TiltedSheet make_tilted_sheet(int n, const Eigen::Matrix3d& rotation, const Vec3& shift,
                              const Vec3& centre, double radius);

}  // namespace rangefill::testing

/// Skips the current test with a message when ../shared/data is absent; else binds `dir` to it.
#define RANGEFILL_REQUIRE_SHARED(dir)                                                  \
  const auto dir##_optional = ::rangefill::testing::shared_data_dir();                 \
  if (!dir##_optional) GTEST_SKIP() << "../shared/data is absent: skipping this test"; \
  const std::filesystem::path& dir = *dir##_optional  // NOLINT(bugprone-macro-parentheses): a name
