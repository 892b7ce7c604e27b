// Punching holes into closed meshes, with the removed faces kept as ground truth (for tests and
// `rangefill bench`). Deterministic for a seed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rangefill/mesh.h"

namespace rangefill {

struct PunchOptions {
  int holes = 5;
  std::uint64_t seed = 1;
  double min_radius = 3;  // geodesic radius, in units of d_m
  double max_radius = 15;
  double separation = 4;  // least geodesic gap between two holes, in units of d_m
  int attempts = 200;     // random centres tried per hole before giving up on it
};

struct PunchedHole {
  int centre = 0;                  // vertex of the input mesh
  double radius = 0;               // geodesic radius (world units)
  std::vector<int> removed_faces;  // faces of the input mesh, ascending
};

struct PunchResult {
  Mesh mesh;                         // the input without the removed faces and their inner vertices
  std::vector<int> original_vertex;  // per vertex of `mesh`, its index in the input
  std::vector<PunchedHole> holes;    // may be fewer than asked when no valid place was found
};

/// Removes geodesic disks (Dijkstra distance along edges from a random vertex, radius uniform in
/// [min_radius, max_radius]·d_m): the faces whose three vertices lie within the radius. A disk is
/// kept only if it is a topological disk (connected, Euler characteristic 1) whose removal adds
/// exactly one boundary loop without a repeated vertex, and if it stays `separation`·d_m away from
/// the holes already made. The remaining vertices keep their order.
PunchResult punch_holes(const Mesh& mesh, const PunchOptions& options);

/// The seed `rangefill bench` punches a mesh named `name` with: `seed` mixed with an FNV-1a hash of
/// the name, so each mesh gets its own holes and adding a mesh changes no other mesh's.
std::uint64_t seed_for_mesh(std::uint64_t seed, const std::string& name);

/// The faces `faces` of `mesh` as a mesh of their own (vertices renumbered in first-use order).
Mesh extract_faces(const Mesh& mesh, const std::vector<int>& faces);

}  // namespace rangefill
