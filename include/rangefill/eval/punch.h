// Punching holes into closed meshes, with the removed faces kept as ground truth (for tests and
// `rangefill bench`). Deterministic for a seed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rangefill/core/mesh.h"

namespace rangefill {

/// The shape of a punched hole: a geodesic disk, or an elongated one (a geodesic capsule: the
/// faces near a shortest path along the edges).
enum class HoleShape { disk, elongated };

/// How much the surface bends over a punched region (Pérez et al., Table 6), by the region's
/// bending: its mean largest principal curvature (curvature.h; over the region's vertices, weighted
/// by their mixed areas) times sqrt(area / π), the radius of a disk of its area. It is about the
/// angle, in radians, by which the normal turns from the region's middle to its rim.
enum class CurvatureClass { low, medium, high };

struct PunchOptions {
  int holes = 5;
  std::uint64_t seed = 1;
  double min_radius = 3;  // disk: geodesic radius; elongated: half its length; in units of d_m
  double max_radius = 15;
  double separation = 4;  // least geodesic gap between two holes, in units of d_m
  int attempts = 200;     // random places tried per hole before giving up on it
  /// Hole k is a shapes[(k + k / 4) % shapes.size()]: with both shapes, a disk and an elongated
  /// hole in turn, so that with `spread` eight holes take every pair of shape and kind.
  std::vector<HoleShape> shapes = {HoleShape::disk};
  double min_aspect = 0.2;  // elongated: half-width / half-length, uniform in [min, max]; the
  double max_aspect = 0.5;  // half-width is at least 2·d_m
  /// Hole k is looked for, in the first half of its attempts, where its region is of the kind
  /// k % 4 of (low, medium, high curvature, sharp feature); then anywhere.
  bool spread = false;
  double low_bending = 0.15;  // a region bending less is of low curvature
  double high_bending = 0.4;  // ... at least this much, of high curvature; medium in between
  double sharp_angle = 40;    // degrees: an edge whose dihedral angle is at least this is sharp
  double sharp_length = 2;    // a region with sharp edges of this total length (in units of d_m)
                              // between two of its faces lies on a sharp feature
};

struct PunchedHole {
  HoleShape shape = HoleShape::disk;
  int centre = 0;     // vertex of the input mesh: a disk's centre, or the middle vertex
                      // of an elongated hole's path
  double radius = 0;  // disk: geodesic radius; elongated: half-width (world units)
  double length = 0;  // elongated: geodesic length of its path (world units); disk: 0
  std::vector<int> removed_faces;  // faces of the input mesh, ascending
  double area = 0;                 // of the removed faces
  double bending = 0;              // see CurvatureClass
  CurvatureClass curvature = CurvatureClass::low;
  bool sharp_feature = false;  // see PunchOptions::sharp_length
};

struct PunchResult {
  Mesh mesh;                         // the input without the removed faces and their inner vertices
  std::vector<int> original_vertex;  // per vertex of `mesh`, its index in the input
  std::vector<PunchedHole> holes;    // may be fewer than asked when no valid place was found
};

/// Removes geodesic disks (Dijkstra distance along edges from a random vertex, radius uniform in
/// [min_radius, max_radius]·d_m): the faces whose three vertices lie within the radius; and, for
/// elongated holes, the faces whose three vertices lie within the half-width w of a shortest path
/// along the edges of length about 2·(L − w), from a random vertex, where the half-length L is
/// uniform in [min_radius, max_radius]·d_m. A region is kept only if it is a topological disk
/// (connected, Euler characteristic 1) whose removal adds exactly one boundary loop without a
/// repeated vertex, and if it stays `separation`·d_m away from the holes already made. Each hole
/// is classified (CurvatureClass, sharp feature). The remaining vertices keep their order.
/// Throws InvalidInput for a mesh without vertices or options out of their ranges.
PunchResult punch_holes(const Mesh& mesh, const PunchOptions& options);

/// What punch_holes does once the regions are chosen: removes every hole's removed_faces (sorted
/// here) and the vertices only they use, and sets each hole's area; the other fields are kept as
/// given. Throws InvalidInput if a face is out of range or in two holes.
PunchResult remove_holes(const Mesh& mesh, std::vector<PunchedHole> holes);

/// "disk", "elongated".
std::string shape_name(HoleShape shape);
/// The shape called `name`; throws InvalidInput otherwise.
HoleShape shape_from_name(const std::string& name);
/// "low", "medium", "high".
std::string curvature_name(CurvatureClass curvature);
/// The class called `name`; throws InvalidInput otherwise.
CurvatureClass curvature_from_name(const std::string& name);

/// The seed `rangefill bench` punches a mesh named `name` with: `seed` mixed with an FNV-1a hash of
/// the name, so each mesh gets its own holes and adding a mesh changes no other mesh's.
std::uint64_t seed_for_mesh(std::uint64_t seed, const std::string& name);

}  // namespace rangefill
