#include "depth/fill_along_lines.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "depth/color_guide.h"
#include "rangefill/core/depth_image.h"
#include "rangefill/core/parallel.h"

namespace rangefill {

namespace {

// A guess at a pixel's inverse depth, its weight and the distance (pixels) of the nearest data
// pixel it comes from.
struct Guess {
  float inverse;
  float weight;
  float distance;
};

// The lines through a pixel: its row, column, diagonal and anti-diagonal.
constexpr int kLines = 4;

// What guesses are made with, computed once: the discontinuity as a ratio of inverse depths, the
// lines' steps, and the reciprocals 1 / n of step counts (no division for each of the pixels).
struct GuessRules {
  float ratio;           // 1 + discontinuity
  const cv::Mat& color;  // CV_32FC3 or empty
  std::array<float, kLines> step_length = {1, 1, std::sqrt(2.0F), std::sqrt(2.0F)};
  std::array<float, kLines> per_squared_step = {1, 1, 0.5F, 0.5F};
  std::vector<float> reciprocal;

  GuessRules(double discontinuity, int longest_line, const cv::Mat& color)
      : ratio(static_cast<float>(1 + discontinuity)),
        color(color),
        reciprocal(longest_line + 1, 0) {
    for (size_t n = 1; n < reciprocal.size(); ++n) reciprocal[n] = 1.0F / static_cast<float>(n);
  }
  // same_surface for inverse depths.
  bool same_surface(float a, float b) const { return std::max(a, b) <= ratio * std::min(a, b); }
  // How much a guess from pixel `end` counts at `pixel`: 1 without colour, else the colour
  // affinity of the two (color_affinity).
  float affinity(cv::Point pixel, cv::Point end) const {
    return color.empty() ? 1.0F
                         : color_affinity(color.at<cv::Vec3f>(pixel), color.at<cv::Vec3f>(end));
  }
};

// A pixel's guesses of one kind, at most 2 a line.
struct Guesses {
  std::array<Guess, 8> guesses;
  int count = 0;
  void add(Guess guess) { guesses[count++] = guess; }

  // Whether guess i counts: without colour, those from at most kFarSurfaceMargin pixels beyond
  // the nearest (a surface seen far away across a large invalid region is not the pixel's); with
  // colour, all, their affinities telling which surface is the pixel's.
  std::array<bool, 8> counted(const GuessRules& rules) const {
    std::array<bool, 8> counts{};
    float nearest = std::numeric_limits<float>::max();
    for (int i = 0; i < count; ++i) nearest = std::min(nearest, guesses[i].distance);
    for (int i = 0; i < count; ++i) {
      counts[i] = (!rules.color.empty()) || guesses[i].distance <= nearest + kFarSurfaceMargin;
    }
    return counts;
  }

  // The surface a pixel takes, as the smallest inverse depth on it: without colour, the farthest
  // of the counted guesses (the background goes on behind an occluder); with colour, the surface
  // whose guesses (rules.same_surface) weigh most, weights holding the colour affinities.
  float surface(const GuessRules& rules, const std::array<bool, 8>& counts) const {
    float best = std::numeric_limits<float>::max(), heaviest = -1;
    for (int i = 0; i < count; ++i) {
      if (!counts[i]) continue;
      if (rules.color.empty()) {
        best = std::min(best, guesses[i].inverse);
        continue;
      }
      float weight = 0, lowest = guesses[i].inverse;
      for (int j = 0; j < count; ++j) {
        if (!rules.same_surface(guesses[i].inverse, guesses[j].inverse)) continue;
        weight += guesses[j].weight;
        lowest = std::min(lowest, guesses[j].inverse);
      }
      if (weight > heaviest) heaviest = weight, best = lowest;
    }
    return best;
  }

  // The weighted mean of the counted guesses on the pixel's surface.
  float surface_mean(const GuessRules& rules) const {
    const std::array<bool, 8> counts = counted(rules);
    const float lowest = surface(rules, counts);
    float sum = 0, weight = 0;
    for (int i = 0; i < count; ++i) {
      if (!counts[i] || !rules.same_surface(guesses[i].inverse, lowest)) continue;
      sum += guesses[i].weight * guesses[i].inverse;
      weight += guesses[i].weight;
    }
    return sum / weight;
  }
};

// The nearest data pixel on one side of a pixel along a line: its inverse depth (0: none) and
// its place along the line (the column on a row, else the row).
struct End {
  float inverse = 0;
  int at = 0;
};

using Ends = std::array<End, kLines>;

// The row of the last data pixel seen on every column (c), diagonal (c − r + rows) and
// anti-diagonal (c + r) of `inverse` (> 0 at data) by a sweep over its rows, as arrays, so that a
// row updates contiguous memory; −1 for none.
class LastSeen {
 public:
  explicit LastSeen(const cv::Mat& inverse)
      : inverse_(inverse), at_(3, std::vector<int>(inverse.rows + inverse.cols, -1)) {}

  // Marks the data pixels of row `row` as last seen on their lines.
  void see_row(int row) {
    see(inverse_.ptr<float>(row), inverse_.cols, row, at_[0].data(),
        at_[1].data() + inverse_.rows - row, at_[2].data() + row);
  }

  // The last data pixels seen on the column and diagonals through (row, col).
  std::array<End, 3> at(int row, int col) const {
    const std::array<int, 3> line = {col, col - row + inverse_.rows, col + row};
    std::array<End, 3> ends;
    for (int kind = 0; kind < 3; ++kind) {
      const int seen_row = at_[kind][line[kind]];
      if (seen_row < 0) continue;
      const int seen_col = col + (kind == 1 ? seen_row - row : kind == 2 ? row - seen_row : 0);
      ends[kind] = {inverse_.at<float>(seen_row, seen_col), seen_row};
    }
    return ends;
  }

 private:
  // Selects over contiguous memory, written so that GCC vectorises them.
  static void see(const float* __restrict values, int cols, int row, int* __restrict column,
                  int* __restrict diagonal, int* __restrict anti_diagonal) {
    for (int col = 0; col < cols; ++col) {
      const int data = -static_cast<int>(values[col] > 0);  // all bits set at data
      column[col] = (row & data) | (column[col] & ~data);
      diagonal[col] = (row & data) | (diagonal[col] & ~data);
      anti_diagonal[col] = (row & data) | (anti_diagonal[col] & ~data);
    }
  }

  const cv::Mat& inverse_;
  std::vector<std::vector<int>> at_;
};

// The pixels to fill of one round, numbered in row-major order from first[row] on each row.
struct Round {
  const cv::Mat& inverse;  // > 0 at data
  const cv::Mat& to_fill;
  std::vector<int> first;  // rows + 1 entries

  Round(const cv::Mat& inverse, const cv::Mat& to_fill)
      : inverse(inverse), to_fill(to_fill), first(to_fill.rows + 1, 0) {
    for (int row = 0; row < to_fill.rows; ++row) {
      first[row + 1] = first[row] + cv::countNonZero(to_fill.row(row));
    }
  }
};

// Calls run(first, last) for every run [first, last) of non-zero bytes of `row` (`cols` long,
// 8 bytes at a time over zeros and over bytes of 255).
template <typename Run>
void for_each_run(const std::uint8_t* row, int cols, Run run) {
  int col = 0;
  while (col < cols) {
    std::uint64_t word = 0;
    while (col + 8 <= cols && (std::memcpy(&word, row + col, 8), word == 0)) col += 8;
    while (col < cols && !row[col]) ++col;
    if (col == cols) return;
    const int first = col;
    while (col + 8 <= cols && (std::memcpy(&word, row + col, 8), word == ~std::uint64_t{0})) {
      col += 8;
    }
    while (col < cols && row[col]) ++col;
    run(first, col);
  }
}

// Rows [begin, end) of the sweep down: the ends above every pixel to fill there (column,
// diagonal, anti-diagonal) into `above`, by its number. The sweep first catches up over the rows
// above `begin`, so that bands of rows can be swept at once.
void sweep_down(const Round& round, int begin, int end, std::vector<std::array<End, 3>>& above) {
  LastSeen seen(round.inverse);
  for (int row = 0; row < end; ++row) {
    seen.see_row(row);
    if (row < begin) continue;
    int next = round.first[row];
    for_each_run(round.to_fill.ptr<std::uint8_t>(row), round.inverse.cols,
                 [&](int first, int last) {
                   for (int col = first; col < last; ++col) above[next++] = seen.at(row, col);
                 });
  }
}

// Rows [begin, end) of the sweep up, after sweep_down: calls settle(pixel, before, after)
// for every pixel to fill there, with its ends on either side of its 4 lines (left or above, right
// or below). Catches up over the rows below `end` first.
template <typename Settle>
void sweep_up(const Round& round, int begin, int end, const std::vector<std::array<End, 3>>& above,
              Settle settle) {
  const int rows = round.inverse.rows, cols = round.inverse.cols;
  LastSeen seen(round.inverse);
  for (int row = rows - 1; row >= begin; --row) {
    const float* values = round.inverse.ptr<float>(row);
    seen.see_row(row);
    if (row >= end) continue;
    // A run's ends on the row: the nearest data pixels beyond it (runs of pixels to fill are
    // mostly bordered by data, so these scans are short).
    const auto data_from = [&](int col, int step) {
      for (; col >= 0 && col < cols; col += step) {
        if (values[col] > 0) return End{values[col], col};
      }
      return End{};
    };
    int next = round.first[row];
    for_each_run(round.to_fill.ptr<std::uint8_t>(row), cols, [&](int first, int last) {
      const End left = data_from(first - 1, -1), right = data_from(last, 1);
      for (int col = first; col < last; ++col) {
        const std::array<End, 3>& up = above[next++];
        const std::array<End, 3> down = seen.at(row, col);
        settle(cv::Point(col, row), Ends{left, up[0], up[1], up[2]},
               Ends{right, down[0], down[1], down[2]});
      }
    });
  }
}

// The pixel of an end of line `line` through `pixel`.
cv::Point end_pixel(const End& end, int line, cv::Point pixel) {
  switch (line) {
    case 0:
      return {end.at, pixel.y};
    case 1:
      return {pixel.x, end.at};
    case 2:
      return {pixel.x + (end.at - pixel.y), end.at};
    default:
      return {pixel.x - (end.at - pixel.y), end.at};
  }
}

// The guesses line `line` gives `pixel` from its ends `a` and `b` (inverse 0: none), added to
// `interpolations` or `constants`: two ends on one surface give the linear interpolation weighted
// by 1 / span², others each a constant weighted by 1 / distance²; each weight times the ends'
// colour affinities to the pixel.
void add_guesses_of_line(End a, End b, cv::Point pixel, int line, const GuessRules& rules,
                         Guesses& interpolations, Guesses& constants) {
  const int at = line == 0 ? pixel.x : pixel.y;
  const float step_length = rules.step_length[line];
  if (a.inverse > 0 && b.inverse > 0 && rules.same_surface(a.inverse, b.inverse)) {
    const float per_step = rules.reciprocal[b.at - a.at];
    const float t = static_cast<float>(at - a.at) * per_step;
    const float affinity = rules.affinity(pixel, end_pixel(a, line, pixel)) *
                           rules.affinity(pixel, end_pixel(b, line, pixel));
    interpolations.add({a.inverse + t * (b.inverse - a.inverse),
                        affinity * per_step * per_step * rules.per_squared_step[line],
                        static_cast<float>(std::min(at - a.at, b.at - at)) * step_length});
    return;
  }
  for (const End& end : {a, b}) {
    if (end.inverse <= 0) continue;
    const int steps = std::abs(at - end.at);
    const float per_step = rules.reciprocal[steps];
    constants.add({end.inverse,
                   rules.affinity(pixel, end_pixel(end, line, pixel)) * per_step * per_step *
                       rules.per_squared_step[line],
                   static_cast<float>(steps) * step_length});
  }
}

}  // namespace

cv::Mat fill_along_lines(const cv::Mat& z, const cv::Mat& data, const cv::Mat& to_fill,
                         double discontinuity, int threads, const cv::Mat& color,
                         cv::Mat* interpolated) {
  CV_Assert(z.type() == CV_32FC1 && data.type() == CV_8UC1 && to_fill.type() == CV_8UC1 &&
            data.size() == z.size() && to_fill.size() == z.size() && threads >= 1 &&
            (color.empty() || (color.type() == CV_32FC3 && color.size() == z.size())));
  if (interpolated != nullptr) *interpolated = cv::Mat::zeros(z.size(), CV_8U);
  cv::Mat inverse(z.size(), CV_32F);
  for (int row = 0; row < z.rows; ++row) {
    const float* depth = z.ptr<float>(row);
    const std::uint8_t* valid = data.ptr<std::uint8_t>(row);
    float* values = inverse.ptr<float>(row);
    for (int col = 0; col < z.cols; ++col) {  // no branch, so that GCC vectorises it
      const float is_data = static_cast<float>(valid[col] != 0);
      values[col] = is_data / (depth[col] + (1 - is_data));  // 1 / z at data, 0 elsewhere
    }
  }
  const GuessRules rules(discontinuity, std::max(z.rows, z.cols), color);
  const int bands = std::min(threads, z.rows);
  const auto band = [&](int b) {
    return static_cast<int>(static_cast<long long>(z.rows) * b / bands);
  };
  cv::Mat filled(z.size(), CV_32F, cv::Scalar(0));  // metres
  cv::Mat left = to_fill != 0;
  for (;;) {
    const Round round(inverse, left);
    if (round.first.back() == 0) break;
    // Results go to `filled`: within a round, pixels fill from data only.
    std::vector<std::array<End, 3>> above(round.first.back());
    parallel_for(bands, threads, [&](int b) { sweep_down(round, band(b), band(b + 1), above); });
    parallel_for(bands, threads, [&](int b) {
      sweep_up(round, band(b), band(b + 1), above,
               [&](cv::Point pixel, const Ends& before, const Ends& after) {
                 Guesses interpolations, constants;
                 for (int line = 0; line < kLines; ++line) {
                   add_guesses_of_line(before[line], after[line], pixel, line, rules,
                                       interpolations, constants);
                 }
                 if (interpolations.count > 0) {
                   filled.at<float>(pixel) = 1 / interpolations.surface_mean(rules);
                   if (interpolated != nullptr) interpolated->at<std::uint8_t>(pixel) = 255;
                 } else if (constants.count > 0) {
                   filled.at<float>(pixel) = 1 / constants.surface_mean(rules);
                 }
               });
    });
    // The pixels filled are data for the next round.
    bool progress = false;
    for (int row = 0; row < z.rows; ++row) {
      const float* metres = filled.ptr<float>(row);
      std::uint8_t* to_fill_next = left.ptr<std::uint8_t>(row);
      float* values = inverse.ptr<float>(row);
      for_each_run(to_fill_next, z.cols, [&](int first, int last) {
        for (int col = first; col < last; ++col) {
          if (metres[col] == 0) continue;
          values[col] = 1 / metres[col];
          to_fill_next[col] = 0;
          progress = true;
        }
      });
    }
    if (!progress) break;
  }
  return filled;
}

}  // namespace rangefill
