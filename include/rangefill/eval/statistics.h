// What a reviewer asks of a comparison of methods on the same holes: how sure a median or a
// share is (percentile bootstrap intervals) and whether one method beats another on the same
// holes (Wilcoxon's signed-rank test).
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

namespace rangefill {

/// A confidence interval; NaN bounds when there is nothing to estimate from.
struct Interval {
  double low = std::numeric_limits<double>::quiet_NaN();
  double high = std::numeric_limits<double>::quiet_NaN();
};

/// Percentile bootstrap interval of the median of `values` at `confidence`: the median of each of
/// `resamples` resamples drawn with replacement, from a generator seeded with `seed` (the same
/// values give the same interval). Throws InvalidInput unless 0 < confidence < 1 and
/// resamples >= 1.
Interval bootstrap_median_interval(const std::vector<double>& values, double confidence = 0.95,
                                   int resamples = 2000, std::uint64_t seed = 1);

/// Percentile bootstrap intervals of the share of the holes among `holes` (indices into
/// `positions`, rank_positions' rows; empty rows, holes no method closed, are left out) on which
/// each of `methods` methods took `position` (1: first), resampling those holes. As above for the
/// arguments; NaN bounds when no hole is ranked.
std::vector<Interval> bootstrap_share_intervals(const std::vector<std::vector<int>>& positions,
                                                const std::vector<int>& holes, int methods,
                                                int position = 1, double confidence = 0.95,
                                                int resamples = 2000, std::uint64_t seed = 1);

/// Wilcoxon's signed-rank test, two-sided, of the paired samples x and y (x[i] − y[i]).
struct SignedRankTest {
  int pairs = 0;         // pairs with a difference: equal pairs are left out
  double statistic = 0;  // W = min(W+, W−), the smaller sum of the ranks of |x − y| by sign
  double p = std::numeric_limits<double>::quiet_NaN();  // NaN without pairs
  bool exact = false;  // p from W's exact distribution (up to 50 pairs, no tied |x − y|), else
                       // its normal approximation with the tie and continuity corrections
};

/// x and y may hold +inf (a method that failed: worse than any value); a pair where both are
/// +inf is equal. Throws InvalidInput if the sizes differ or a value is NaN.
SignedRankTest wilcoxon_signed_rank(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace rangefill
