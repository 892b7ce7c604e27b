// Builds a grid with one missing quad through the installed API and checks that it finds 2 loops.
#include <cstdio>

#include <rangefill/hole/holes.h>
#include <rangefill/io/mesh_io.h>

int main() {
  using namespace rangefill;
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) positions.emplace_back(x, y, 0);
  }
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 3; ++x) {
      if (x == 1 && y == 1) continue;
      const int a = y * 4 + x;
      triangles.push_back({a, a + 1, a + 5});
      triangles.push_back({a, a + 5, a + 4});
    }
  }
  const Mesh mesh = make_mesh(positions, triangles);
  const Mesh back = parse_mesh(serialize_mesh(mesh, MeshFormat::ply), MeshFormat::ply, "grid").mesh;
  const HoleSet holes = find_holes(back, build_topology(back));
  std::printf("%zu loops\n", holes.loops.size());
  return holes.loops.size() == 2 ? 0 : 1;
}
