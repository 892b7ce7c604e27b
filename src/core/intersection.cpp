#include "rangefill/core/intersection.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <numeric>

#include <CGAL/box_intersection_d.h>

#include "core/cgal_triangles.h"
#include "rangefill/core/parallel.h"

namespace rangefill {

using namespace cgal_triangles;

// The faces in uniform grids: grid k has cubes of 3·4^k times the mean face extent and holds the
// faces too large for grid k − 1, each in the cell of its bounding box's low corner. A grid hashes
// its cells into buckets, filled by a counting sort. A query reads, in each grid, the cells its
// own box meets and those one cell lower, so its cost follows the faces near it, not the mesh,
// whatever the spread of the face sizes. With regions, a coarse grid over the mesh (the cover)
// marks the cells the regions meet; the grids hold the faces whose box meets a marked cell, which
// are all the faces a query can meet when every cell of its box is marked.
struct IntersectionIndex::Tree {
  struct Grid {
    double cell = 1;
    std::vector<int> bucket_offsets;   // CSR over the buckets, size B + 1
    std::vector<std::uint64_t> cells;  // cell key of each entry, grouped by bucket
    std::vector<int> faces;            // face of each entry
    size_t bucket(std::uint64_t key) const {
      return (key * 0x9E3779B97F4A7C15ull >> 20) % (bucket_offsets.size() - 1);
    }
  };
  static constexpr long long kAxisCells = 1 << 21;
  static constexpr long long kCoverAxisCells = 128;
  using Cells = std::array<std::array<long long, 2>, 3>;  // first and last cell on each axis

  const Mesh& mesh;
  std::vector<std::array<Vec3, 2>> regions;  // none: every face in the grids
  std::once_flag built;  // the grids are built on the first query, by whichever thread asks
  Vec3 origin = Vec3::Zero();
  std::vector<Grid> grids;
  Vec3 cover_origin = Vec3::Zero();
  double cover_cell = 1;
  std::vector<bool> cover;  // per cell of the cover, row-major: a region meets it

  Tree(const Mesh& indexed_mesh, std::vector<std::array<Vec3, 2>> near)
      : mesh(indexed_mesh), regions(std::move(near)) {}

  std::pair<Vec3, Vec3> box(int face) const {
    const Triangle& t = mesh.triangles[face];
    const Vec3 &p = mesh.positions[t[0]], &q = mesh.positions[t[1]], &r = mesh.positions[t[2]];
    return {p.cwiseMin(q).cwiseMin(r), p.cwiseMax(q).cwiseMax(r)};
  }
  static Cells cells(const Vec3& low, const Vec3& high, const Vec3& from, double cell,
                     long long axis_cells) {
    Cells range;
    for (int axis = 0; axis < 3; ++axis) {
      for (int side = 0; side < 2; ++side) {
        double at = std::floor(((side ? high : low)[axis] - from[axis]) / cell);
        if (std::isnan(at)) at = side ? axis_cells : 0;  // all cells
        range[axis][side] =
            static_cast<long long>(std::clamp(at, 0.0, static_cast<double>(axis_cells - 1)));
      }
    }
    return range;
  }
  Cells cells(const Vec3& low, const Vec3& high, double cell) const {
    return cells(low, high, origin, cell, kAxisCells);
  }
  // Key of the cell of grid `level` that holds `face`: that of its box's low corner.
  std::uint64_t cell_of(int face, size_t level) const {
    const Vec3 low = box(face).first;
    const Cells at = cells(low, low, grids[level].cell);
    return key(at[0][0], at[1][0], at[2][0]);
  }
  static long long count(const Cells& range) {
    long long n = 1;
    for (const auto& [first, last] : range) n *= last - first + 1;
    return n;
  }
  static std::uint64_t key(long long x, long long y, long long z) {
    return static_cast<std::uint64_t>(x | y << 21 | z << 42);
  }

  // Calls visit(i) for the index i of each cell of the cover that [low, high] meets, in order,
  // while it returns true; whether it did for every cell.
  template <typename Visit>
  bool every_cover_cell(const Vec3& low, const Vec3& high, Visit visit) const {
    const Cells range = cells(low, high, cover_origin, cover_cell, kCoverAxisCells);
    for (long long z = range[2][0]; z <= range[2][1]; ++z) {
      for (long long y = range[1][0]; y <= range[1][1]; ++y) {
        for (long long x = range[0][0]; x <= range[0][1]; ++x) {
          if (!visit((z * kCoverAxisCells + y) * kCoverAxisCells + x)) return false;
        }
      }
    }
    return true;
  }

  // Whether a query over [low, high] may read the grids alone.
  bool answers(const Vec3& low, const Vec3& high) const {
    return regions.empty() ||
           every_cover_cell(low, high, [&](long long cell) { return cover[cell]; });
  }

  // The faces the grids hold: every face, or those near the regions.
  std::vector<int> faces_to_index() {
    std::vector<int> faces;
    if (regions.empty()) {
      faces.resize(mesh.face_count());
      std::iota(faces.begin(), faces.end(), 0);
      return faces;
    }
    const auto [low, high] = bounding_box(mesh);
    cover_origin = low;
    cover_cell =
        std::max((high - low).maxCoeff() / kCoverAxisCells, std::numeric_limits<double>::min());
    cover.assign(kCoverAxisCells * kCoverAxisCells * kCoverAxisCells, false);
    for (const auto& [region_low, region_high] : regions) {
      every_cover_cell(region_low, region_high, [&](long long cell) {
        cover[cell] = true;
        return true;
      });
    }
    const int face_count = mesh.face_count();
    std::vector<std::vector<int>> found(kMeshRanges);
    parallel_for(kMeshRanges, mesh_pass_threads(face_count), [&](int r) {
      for (int face = range_begin(face_count, r); face < range_begin(face_count, r + 1); ++face) {
        const auto [face_low, face_high] = box(face);
        const bool meets_cover =
            !every_cover_cell(face_low, face_high, [&](long long cell) { return !cover[cell]; });
        if (meets_cover) found[r].push_back(face);
      }
    });
    for (const std::vector<int>& near : found) faces.insert(faces.end(), near.begin(), near.end());
    return faces;
  }

  // Each face's box is recomputed rather than stored, here and below: building holds little
  // beyond the entries (a key and a face each), which the peak memory of a large repair feels.
  void build() {
    const std::vector<int> faces = faces_to_index();
    if (faces.empty()) return;
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::max()), high = -low;
    double extent = 0;
    const auto extent_of = [&](int face) {
      const auto [face_low, face_high] = box(face);
      return (face_high - face_low).maxCoeff();
    };
    for (const int face : faces) {
      const auto [face_low, face_high] = box(face);
      low = low.cwiseMin(face_low);
      high = high.cwiseMax(face_high);
      extent += (face_high - face_low).maxCoeff();
    }
    origin = low;
    // No more than kAxisCells cells along an axis.
    const double first_cell =
        std::max({3 * extent / static_cast<double>(faces.size()),
                  (high - low).maxCoeff() / (kAxisCells - 2), std::numeric_limits<double>::min()});
    std::vector<std::uint8_t> levels(faces.size());
    std::vector<int> level_sizes;
    for (size_t i = 0; i < faces.size(); ++i) {
      const double face_extent = extent_of(faces[i]);
      size_t level = 0;
      while (level < grids.size() && grids[level].cell < face_extent) ++level;
      while (level == grids.size() || grids[level].cell < face_extent) {
        grids.push_back({grids.empty() ? first_cell : 4 * grids.back().cell, {}, {}, {}});
        level_sizes.push_back(0);
        level = grids.size() - 1;
      }
      levels[i] = static_cast<std::uint8_t>(level);
      ++level_sizes[level];
    }
    for (size_t level = 0; level < grids.size(); ++level) {
      grids[level].bucket_offsets.assign(static_cast<size_t>(level_sizes[level]) + 2, 0);
      grids[level].cells.resize(level_sizes[level]);
      grids[level].faces.resize(level_sizes[level]);
    }
    for (size_t i = 0; i < faces.size(); ++i) {
      Grid& grid = grids[levels[i]];
      ++grid.bucket_offsets[grid.bucket(cell_of(faces[i], levels[i])) + 1];
    }
    for (Grid& grid : grids) {
      std::partial_sum(grid.bucket_offsets.begin(), grid.bucket_offsets.end(),
                       grid.bucket_offsets.begin());
    }
    std::vector<std::vector<int>> cursors(grids.size());
    for (size_t level = 0; level < grids.size(); ++level) {
      cursors[level].assign(grids[level].bucket_offsets.begin(),
                            grids[level].bucket_offsets.end() - 1);
    }
    for (size_t i = 0; i < faces.size(); ++i) {
      Grid& grid = grids[levels[i]];
      const std::uint64_t cell = cell_of(faces[i], levels[i]);
      const int entry = cursors[levels[i]][grid.bucket(cell)]++;
      grid.cells[entry] = cell;
      grid.faces[entry] = faces[i];
    }
  }

  // The faces the grids hold near [low, high] (each once, unordered), or every face when the
  // grids do not answer for it.
  std::vector<int> faces_near(const Vec3& low, const Vec3& high) const {
    std::vector<int> faces;
    if (!answers(low, high)) {
      faces.resize(mesh.face_count());
      std::iota(faces.begin(), faces.end(), 0);
      return faces;
    }
    for (const Grid& grid : grids) {
      const Cells range = cells(low - Vec3::Constant(grid.cell), high, grid.cell);
      if (count(range) > static_cast<long long>(grid.cells.size())) {  // read them all
        faces.insert(faces.end(), grid.faces.begin(), grid.faces.end());
        continue;
      }
      for (long long z = range[2][0]; z <= range[2][1]; ++z) {
        for (long long y = range[1][0]; y <= range[1][1]; ++y) {
          for (long long x = range[0][0]; x <= range[0][1]; ++x) {
            const std::uint64_t cell = key(x, y, z);
            const size_t bucket = grid.bucket(cell);
            for (int i = grid.bucket_offsets[bucket]; i < grid.bucket_offsets[bucket + 1]; ++i) {
              if (grid.cells[i] == cell) faces.push_back(grid.faces[i]);
            }
          }
        }
      }
    }
    return faces;
  }

  // Faces whose bounding box meets [low, high], each once, unordered.
  std::vector<int> candidates(const Vec3& low, const Vec3& high) const {
    std::vector<int> faces = faces_near(low, high);
    faces.erase(std::remove_if(faces.begin(), faces.end(),
                               [&](int face) {
                                 const auto [face_low, face_high] = box(face);
                                 return (face_low.array() > high.array()).any() ||
                                        (face_high.array() < low.array()).any();
                               }),
                faces.end());
    return faces;
  }
};

IntersectionIndex::IntersectionIndex(const Mesh& mesh)
    : tree_(std::make_unique<Tree>(mesh, std::vector<std::array<Vec3, 2>>())) {}

IntersectionIndex::IntersectionIndex(const Mesh& mesh, std::vector<std::array<Vec3, 2>> regions)
    : tree_(std::make_unique<Tree>(mesh, std::move(regions))) {}

IntersectionIndex::~IntersectionIndex() = default;
IntersectionIndex::IntersectionIndex(IntersectionIndex&&) noexcept = default;
IntersectionIndex& IntersectionIndex::operator=(IntersectionIndex&&) noexcept = default;

namespace {

// Whether r and s lie on opposite sides of the line pq, certainly: the normals of (p, q, r) and
// (p, q, s) point apart by more than the rounding of their dot product can hide (a filter before
// CGAL's exact predicates, which subdivided meshes, flat across their edges, send to exact
// arithmetic on every pair of neighbours).
bool on_opposite_sides(const Point& p, const Point& q, const Point& r, const Point& s) {
  const Vec3 a(p.x(), p.y(), p.z()), b(q.x(), q.y(), q.z());
  const Vec3 c(r.x(), r.y(), r.z()), d(s.x(), s.y(), s.z());
  const Vec3 edge = b - a, to_r = c - a, to_s = d - a;
  const double dot = edge.cross(to_r).dot(edge.cross(to_s));
  // The differences err by up to 2^-52 of the largest coordinate, the products by a few units of
  // 2^-52 of their size: 1e-14 and 1e-12 are far beyond both.
  const double largest = std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(),
                                   c.cwiseAbs().maxCoeff(), d.cwiseAbs().maxCoeff()});
  const double e = edge.norm(), u = to_r.norm(), v = to_s.norm();
  const double bound = 1e-12 * e * e * u * v + 1e-14 * largest * (2 * e * u * v + e * e * (u + v));
  return dot < -bound;
}

// Whether the segment cd certainly misses the triangle (p, a, b): along the triangle's normal, or
// along a direction of its plane across one of its edges or across the segment, the segment's
// ends and the triangle's corners project to intervals apart by more than rounding can hide (the
// separating axes of the two, seen along the normal where they are coplanar). It filters the pairs
// of faces round a shared vertex p before CGAL's do_intersect, which decides every such pair of a
// subdivided mesh (flat round its vertices) in exact arithmetic.
bool certainly_misses(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 pa = a - p, pb = b - p, pc = c - p, pd = d - p;
  const Vec3 normal = pa.cross(pb);
  // A projection axis·(x − p) errs by a few units of 2^-52 of |axis| L (L the longest difference)
  // and, through the rounding of the differences, of the largest coordinate times |axis|, which
  // is at most L² for the normal and 2L³ across it: 1e-12 and 1e-13 are far beyond both.
  const double longest = std::max({pa.norm(), pb.norm(), pc.norm(), pd.norm()});
  const double largest =
      std::max({p.cwiseAbs().maxCoeff(), a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(),
                c.cwiseAbs().maxCoeff(), d.cwiseAbs().maxCoeff()});
  const auto separates = [&](const Vec3& axis, double axis_bound) {
    const double bound = axis_bound * (1e-12 * longest + 1e-13 * largest);
    const double at_a = axis.dot(pa), at_b = axis.dot(pb);  // p projects to 0
    const double at_c = axis.dot(pc), at_d = axis.dot(pd);
    return std::min(at_c, at_d) > std::max({0.0, at_a, at_b}) + bound ||
           std::max(at_c, at_d) < std::min({0.0, at_a, at_b}) - bound;
  };
  const double square = longest * longest, across_bound = 2 * square * longest;
  return separates(normal, square) || separates(normal.cross(pa), across_bound) ||
         separates(normal.cross(pb), across_bound) ||
         separates(normal.cross(Vec3(b - a)), across_bound) ||
         separates(normal.cross(Vec3(d - c)), across_bound);
}

// Whether triangles t (query) and u (a face), which meet and share the vertices marked in
// shared_t / shared_u, intersect elsewhere, as CGAL's self_intersections decides: sharing one
// vertex, an edge opposite it crosses the other triangle; sharing an edge, they are coplanar and
// folded onto each other; sharing all three, they are the same face.
bool meet_beyond_shared(const std::array<Point, 3>& t, const std::array<Point, 3>& u,
                        const std::array<bool, 3>& shared_t, const std::array<bool, 3>& shared_u) {
  const int count = static_cast<int>(std::count(shared_t.begin(), shared_t.end(), true));
  if (count == 0 || count == 3) return true;
  const auto index_of = [](const std::array<bool, 3>& marks, bool value) {
    return static_cast<int>(std::find(marks.begin(), marks.end(), value) - marks.begin());
  };
  if (count == 1) {
    const int i = index_of(shared_t, true), j = index_of(shared_u, true);
    const auto vec = [](const Point& point) { return Vec3(point.x(), point.y(), point.z()); };
    if (certainly_misses(vec(u[j]), vec(u[(j + 1) % 3]), vec(u[(j + 2) % 3]), vec(t[(i + 1) % 3]),
                         vec(t[(i + 2) % 3])) &&
        certainly_misses(vec(t[i]), vec(t[(i + 1) % 3]), vec(t[(i + 2) % 3]), vec(u[(j + 1) % 3]),
                         vec(u[(j + 2) % 3]))) {
      return false;  // the usual case, without exact steps
    }
    const CgalTriangle triangle_t(t[0], t[1], t[2]), triangle_u(u[0], u[1], u[2]);
    return CGAL::do_intersect(Segment(t[(i + 1) % 3], t[(i + 2) % 3]), triangle_u) ||
           CGAL::do_intersect(Segment(u[(j + 1) % 3], u[(j + 2) % 3]), triangle_t);
  }
  const int i = index_of(shared_t, false), j = index_of(shared_u, false);
  const Point &p = t[(i + 1) % 3], &q = t[(i + 2) % 3];
  if (on_opposite_sides(p, q, t[i], u[j])) return false;  // the usual case, without exact steps
  return CGAL::coplanar(p, q, t[i], u[j]) &&
         CGAL::coplanar_orientation(p, q, t[i], u[j]) == CGAL::POSITIVE;
}

// Whether triangles t and u meet at all: certainly when they share a corner (marked in shared_t).
bool meets(const CgalTriangle& t, const CgalTriangle& u, const std::array<bool, 3>& shared_t) {
  return std::count(shared_t.begin(), shared_t.end(), true) > 0 || CGAL::do_intersect(t, u);
}

// Which corners of t and of u are the same vertex: the same id (-1 is no vertex), or two vertices
// at the same point (a surface that touches itself there, as a welded mesh would share them).
std::pair<std::array<bool, 3>, std::array<bool, 3>> shared_corners(
    const Triangle& t, const std::array<Point, 3>& t_points, const Triangle& u,
    const std::array<Point, 3>& u_points) {
  std::array<bool, 3> shared_t{}, shared_u{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (t[i] >= 0 && u[j] >= 0 && (t[i] == u[j] || t_points[i] == u_points[j])) {
        shared_t[i] = shared_u[j] = true;
      }
    }
  }
  return {shared_t, shared_u};
}

}  // namespace

std::vector<int> IntersectionIndex::intersecting_faces(const Vec3& a, const Vec3& b, const Vec3& c,
                                                       const Triangle& corners) const {
  std::vector<int> faces;
  if (tree_->mesh.triangles.empty()) return faces;
  std::call_once(tree_->built, [this] { tree_->build(); });
  const std::array<Point, 3> query = {to_point(a), to_point(b), to_point(c)};
  const CgalTriangle triangle(query[0], query[1], query[2]);
  if (triangle.is_degenerate()) return faces;
  for (const int face : tree_->candidates(a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c))) {
    const Triangle& u = tree_->mesh.triangles[face];
    const std::array<Point, 3> other = {to_point(tree_->mesh.positions[u[0]]),
                                        to_point(tree_->mesh.positions[u[1]]),
                                        to_point(tree_->mesh.positions[u[2]])};
    const CgalTriangle other_triangle(other[0], other[1], other[2]);
    if (other_triangle.is_degenerate()) continue;
    const auto [shared_query, shared_face] = shared_corners(corners, query, u, other);
    if (meets(triangle, other_triangle, shared_query) &&
        meet_beyond_shared(query, other, shared_query, shared_face)) {
      faces.push_back(face);
    }
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

bool triangles_intersect(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b,
                         const Triangle& ids_a, const Triangle& ids_b) {
  const std::array<Point, 3> first = {to_point(a[0]), to_point(a[1]), to_point(a[2])};
  const std::array<Point, 3> second = {to_point(b[0]), to_point(b[1]), to_point(b[2])};
  const CgalTriangle triangle_a(first[0], first[1], first[2]);
  const CgalTriangle triangle_b(second[0], second[1], second[2]);
  if (triangle_a.is_degenerate() || triangle_b.is_degenerate()) return false;
  const auto [shared_a, shared_b] = shared_corners(ids_a, first, ids_b, second);
  return meets(triangle_a, triangle_b, shared_a) &&
         meet_beyond_shared(first, second, shared_a, shared_b);
}

// The pairs of faces whose boxes meet come from CGAL's box intersection (a sweep over sorted
// boxes), each pair once: a query per face would read its grid cells and their faces again and
// again. The boxes are floats rounded outwards: half the memory, and
// a pair they add is refused by the exact test.
int count_self_intersections(const Mesh& mesh, const std::vector<int>& faces) {
  using FaceBox =
      CGAL::Box_intersection_d::Box_with_handle_d<float, 3, const Triangle*,
                                                  CGAL::Box_intersection_d::ID_FROM_HANDLE>;
  const auto box_of = [&](int face) {
    const Triangle& t = mesh.triangles[face];
    Vec3 low = mesh.positions[t[0]], high = low;
    for (int corner : {t[1], t[2]}) {
      low = low.cwiseMin(mesh.positions[corner]);
      high = high.cwiseMax(mesh.positions[corner]);
    }
    constexpr float kInfinity = std::numeric_limits<float>::infinity();
    std::array<float, 3> float_low, float_high;
    for (int axis = 0; axis < 3; ++axis) {
      float_low[axis] = std::nextafter(static_cast<float>(low[axis]), -kInfinity);
      float_high[axis] = std::nextafter(static_cast<float>(high[axis]), kInfinity);
    }
    return FaceBox(float_low.data(), float_high.data(), &t);
  };
  const auto face_of = [&](const FaceBox& box) {
    return static_cast<int>(box.handle() - mesh.triangles.data());
  };
  const auto intersect = [&](int face, int other) {
    const Triangle &t = mesh.triangles[face], &u = mesh.triangles[other];
    return triangles_intersect({mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]},
                               {mesh.positions[u[0]], mesh.positions[u[1]], mesh.positions[u[2]]},
                               t, u);
  };
  std::vector<bool> queried(mesh.triangles.size(), false);
  for (int face : faces) queried[face] = true;
  std::vector<FaceBox> all_boxes, queried_boxes;
  all_boxes.reserve(mesh.triangles.size());
  for (int face = 0; face < mesh.face_count(); ++face) all_boxes.push_back(box_of(face));
  int count = 0;
  if (std::find(queried.begin(), queried.end(), false) == queried.end()) {  // each pair once
    CGAL::box_self_intersection_d(
        all_boxes.begin(), all_boxes.end(),
        [&](const FaceBox& a, const FaceBox& b) { count += intersect(face_of(a), face_of(b)); });
    return count;
  }
  for (int face = 0; face < mesh.face_count(); ++face) {
    if (queried[face]) queried_boxes.push_back(all_boxes[face]);
  }
  // A pair of queried faces comes twice, once from each.
  CGAL::box_intersection_d(queried_boxes.begin(), queried_boxes.end(), all_boxes.begin(),
                           all_boxes.end(), [&](const FaceBox& a, const FaceBox& b) {
                             const int face = face_of(a), other = face_of(b);
                             if (other == face || (queried[other] && other < face)) return;
                             count += intersect(face, other);
                           });
  return count;
}

}  // namespace rangefill
