#include "support.h"

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>

#include <gtest/gtest.h>

#include "rangefill/repair/filler_options.h"

namespace rangefill::testing {

namespace fs = std::filesystem;

std::optional<fs::path> shared_data_dir() {
  const fs::path dir = fs::path(RANGEFILL_SHARED_DIR) / "data";
  if (fs::is_directory(dir / "meshes")) return dir;
  return std::nullopt;
}

fs::path temporary_directory(const std::string& stem) {
  static std::atomic<int> counter{0};
  fs::path dir =
      fs::temp_directory_path() /
      ("rangefill-" + stem + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

Vec3 round_to_float(const Vec3& v) {
  volatile float x = static_cast<float>(v.x()), y = static_cast<float>(v.y()),
                 z = static_cast<float>(v.z());
  return {x, y, z};
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

Mesh make_sphere(int frequency) {
  const double phi = (1 + std::sqrt(5.0)) / 2;
  const std::vector<Vec3> corners = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                                     {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                                     {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  const std::vector<Triangle> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  std::vector<Vec3> positions;
  std::map<std::array<long long, 3>, int> index_of;  // vertices shared along icosahedron edges
  auto vertex = [&](const Vec3& p) {
    const Vec3 unit = p.normalized();
    const std::array<long long, 3> key = {
        std::llround(unit.x() * 1e9), std::llround(unit.y() * 1e9), std::llround(unit.z() * 1e9)};
    const auto found = index_of.find(key);
    if (found != index_of.end()) return found->second;
    positions.push_back(unit);
    return index_of[key] = static_cast<int>(positions.size()) - 1;
  };
  std::vector<Triangle> triangles;
  const int n = frequency;
  for (const Triangle& f : faces) {
    const Vec3 &a = corners[f[0]], &b = corners[f[1]], &c = corners[f[2]];
    auto at = [&](int i, int j) {
      return vertex(a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n));
    };
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 1 < n) triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  }
  return make_mesh(positions, triangles);
}

Mesh make_sphere_cloud(int n, double cut) {
  const double golden_angle = M_PI * (3 - std::sqrt(5.0));
  Mesh cloud;
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (i + 0.5) * 2.0 / n, r = std::sqrt(1 - z * z);
    if (z > cut) continue;
    add_vertex(cloud, Vec3(r * std::cos(golden_angle * i), r * std::sin(golden_angle * i), z),
               kOriginal);
  }
  return cloud;
}

Mesh make_revolution(const std::vector<Eigen::Vector2d>& profile, int segments) {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  const int last = static_cast<int>(profile.size()) - 1;
  // Ring i holds `segments` vertices, a pole one; vertex(i, k) wraps round in k.
  std::vector<int> first(profile.size());
  for (int i = 0; i <= last; ++i) {
    first[i] = static_cast<int>(positions.size());
    const int count = i == 0 || i == last ? 1 : segments;
    for (int k = 0; k < count; ++k) {
      const double angle = 2 * M_PI * k / segments;
      positions.emplace_back(profile[i].x() * std::cos(angle), profile[i].x() * std::sin(angle),
                             profile[i].y());
    }
  }
  auto vertex = [&](int i, int k) {
    return i == 0 || i == last ? first[i] : first[i] + k % segments;
  };
  for (int i = 0; i < last; ++i) {
    for (int k = 0; k < segments; ++k) {
      // The quad a b (ring i) c d (ring i + 1): (b - a) × (c - a) points outwards.
      const int a = vertex(i, k), b = vertex(i, k + 1), c = vertex(i + 1, k),
                d = vertex(i + 1, k + 1);
      if (i > 0) triangles.push_back({a, b, c});
      if (i + 1 < last) triangles.push_back({b, d, c});
    }
  }
  return make_mesh(positions, triangles);
}

namespace {

// The (radius, z) profile of make_capsule, pole to pole.
std::vector<Eigen::Vector2d> capsule_profile(double radius, double half_length, double step) {
  std::vector<Eigen::Vector2d> profile;
  const int arc = std::max(2, static_cast<int>(std::lround(M_PI / 2 * radius / step)));
  const int straight = std::max(1, static_cast<int>(std::lround(2 * half_length / step)));
  for (int k = 0; k <= arc; ++k) {  // bottom hemisphere, from the pole
    const double angle = M_PI / 2 * k / arc;
    profile.emplace_back(radius * std::sin(angle), -half_length - radius * std::cos(angle));
  }
  for (int k = 1; k < straight; ++k) {
    profile.emplace_back(radius, -half_length + 2 * half_length * k / straight);
  }
  for (int k = arc; k >= 0; --k) {  // top hemisphere, to the pole
    const double angle = M_PI / 2 * k / arc;
    profile.emplace_back(radius * std::sin(angle), half_length + radius * std::cos(angle));
  }
  profile.front().x() = profile.back().x() = 0;
  return profile;
}

}  // namespace

Mesh make_capsule(double radius, double half_length, double step) {
  return make_revolution(capsule_profile(radius, half_length, step),
                         static_cast<int>(std::lround(2 * M_PI * radius / step)));
}

Mesh make_double_cone(double rim, double height, int steps, int segments) {
  std::vector<Eigen::Vector2d> profile;
  for (int k = 0; k <= steps; ++k)
    profile.emplace_back(rim * k / steps, -height * (steps - k) / steps);
  for (int k = steps - 1; k >= 0; --k)
    profile.emplace_back(rim * k / steps, height * (steps - k) / steps);
  return make_revolution(profile, segments);
}

double azimuth_degrees(const Vec3& p) {
  const double angle = std::atan2(p.y(), p.x()) * 180 / M_PI;
  return angle < 0 ? angle + 360 : angle;
}

RepairOptions paper_chain(const PlaneFillerOptions& plane) {
  FillerOptions fillers;
  fillers.plane = plane;
  RepairOptions options;
  options.chain = make_filler_chain("plane", "front,least-area", fillers);
  options.selection.candidates.clear();  // the chain alone
  return options;
}

PlaneFillerOptions plane_options(const std::string& inpainter, TrendKind trend) {
  PlaneFillerOptions plane;
  plane.inpainter = inpainter;
  plane.trend = trend;
  return plane;
}

Mesh make_box(int n) {
  const Mesh grid = make_grid(n);
  // Grid (u, v) onto each side; each map turns the grid's +z into the side's outward normal.
  const std::vector<std::function<Vec3(double, double)>> sides = {[](double u, double v) { return Vec3(u, v, 1); },
                                                                  [](double u, double v) { return Vec3(v, u, 0); },
                                                                  [](double u, double v) { return Vec3(1, u, v); },
                                                                  [](double u, double v) { return Vec3(0, v, u); },
                                                                  [](double u, double v) { return Vec3(v, 1, u); },
                                                                  [](double u, double v) { return Vec3(u, 0, v); }};
  std::vector<Vec3> positions;
  std::map<std::array<long long, 3>, int> index_of;  // vertices shared along the edges
  std::vector<Triangle> triangles;
  for (const auto& side : sides) {
    std::vector<int> id;
    for (const Vec3& p : grid.positions) {
      const Vec3 q = side(p.x() / n, p.y() / n);
      const std::array<long long, 3> key = {std::llround(q.x() * n), std::llround(q.y() * n),
                                            std::llround(q.z() * n)};
      const auto [entry, inserted] = index_of.try_emplace(key, static_cast<int>(positions.size()));
      if (inserted) positions.push_back(q);
      id.push_back(entry->second);
    }
    for (const Triangle& t : grid.triangles) triangles.push_back({id[t[0]], id[t[1]], id[t[2]]});
  }
  return make_mesh(positions, triangles);
}

void remove_grid_quad(Mesh& mesh, int n, int x, int y) {
  const int first = 2 * (y * n + x);
  mesh.triangles.erase(mesh.triangles.begin() + first, mesh.triangles.begin() + first + 2);
  mesh.face_hole.resize(mesh.triangles.size());
}

BoundaryLoop inner_loop(const Mesh& mesh) {
  BoundaryLoop hole;
  hole.area_share = std::numeric_limits<double>::infinity();
  for (const BoundaryLoop& loop : find_holes(mesh, build_topology(mesh)).loops) {
    if (loop.area_share < hole.area_share) hole = loop;
  }
  return hole;
}

double smallest_angle(const Mesh& mesh, const Fill& fill) {
  const auto position = [&](int v) {
    const int boundary_size = static_cast<int>(fill.boundary.size());
    return v < boundary_size ? mesh.positions[fill.boundary[v]] : fill.points[v - boundary_size];
  };
  double smallest = 180;
  for (const Triangle& t : fill.triangles) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 u = position(t[(k + 1) % 3]) - position(t[k]);
      const Vec3 v = position(t[(k + 2) % 3]) - position(t[k]);
      smallest = std::min(smallest, std::atan2(u.cross(v).norm(), u.dot(v)) * 180 / M_PI);
    }
  }
  return smallest;
}

void expect_bit_identical(const std::vector<Vec3>& actual, const std::vector<Vec3>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t i = 0; i < actual.size(); ++i) {
    EXPECT_EQ(std::memcmp(actual[i].data(), expected[i].data(), sizeof(double) * 3), 0)
        << "element " << i << ": " << actual[i].transpose() << " vs " << expected[i].transpose();
  }
}

void expect_input_preserved(const Mesh& input, const Mesh& output) {
  ASSERT_GE(output.vertex_count(), input.vertex_count());
  ASSERT_GE(output.face_count(), input.face_count());
  expect_bit_identical({output.positions.begin(), output.positions.begin() + input.vertex_count()},
                       input.positions);
  EXPECT_TRUE(std::equal(input.triangles.begin(), input.triangles.end(), output.triangles.begin()));
  for (int v = input.vertex_count(); v < output.vertex_count(); ++v) {
    EXPECT_NE(output.vertex_hole[v], kOriginal) << "vertex " << v;
  }
}

TiltedSheet make_tilted_sheet(int n, const Eigen::Matrix3d& rotation, const Vec3& shift,
                              const Vec3& centre, double radius) {
  TiltedSheet sheet;
  sheet.rotation = rotation;
  sheet.shift = shift;
  Mesh grid = make_grid(n);
  for (Vec3& p : grid.positions) p = rotation * p + shift;
  sheet.mesh = remove_faces(grid, [&](const Vec3& p) {
    return (rotation.transpose() * (p - shift) - centre).norm() < radius;
  });
  sheet.hole = inner_loop(sheet.mesh);
  for (int f = 0; f < sheet.mesh.face_count(); ++f) sheet.zone.faces.push_back(f);
  for (int v = 0; v < sheet.mesh.vertex_count(); ++v) sheet.zone.vertices.push_back(v);
  const auto [lo, hi] = bounding_box(sheet.mesh);
  sheet.size = (hi - lo).norm();
  return sheet;
}

}  // namespace rangefill::testing
