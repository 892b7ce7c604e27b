#include "rangefill/eval/statistics.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "rangefill/core/errors.h"

namespace rangefill {

namespace {

void check_bootstrap(double confidence, int resamples) {
  if (!(confidence > 0 && confidence < 1) || resamples < 1) {
    throw InvalidInput("bootstrap: confidence must lie in (0, 1) and resamples be at least 1");
  }
}

double median_of(std::vector<double>& values) {
  const size_t half = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + half, values.end());
  const double upper = values[half];
  if (values.size() % 2 == 1) return upper;
  return (*std::max_element(values.begin(), values.begin() + half) + upper) / 2;
}

// The (1 − confidence)/2 and (1 + confidence)/2 quantiles of `estimates` (sorted here), each the
// nearest order statistic.
Interval percentile_interval(std::vector<double>& estimates, double confidence) {
  std::sort(estimates.begin(), estimates.end());
  const double last = static_cast<double>(estimates.size() - 1);
  const auto at = [&](double q) { return estimates[static_cast<size_t>(std::lround(q * last))]; };
  return {at((1 - confidence) / 2), at((1 + confidence) / 2)};
}

// An index in [0, n) from `random`, the same on every platform (unlike the standard
// distributions): Lemire's multiply-shift, whose bias is below n / 2^64.
size_t draw(std::mt19937_64& random, size_t n) {
  return static_cast<size_t>((static_cast<unsigned __int128>(random()) * n) >> 64);
}

}  // namespace

Interval bootstrap_median_interval(const std::vector<double>& values, double confidence,
                                   int resamples, std::uint64_t seed) {
  check_bootstrap(confidence, resamples);
  if (values.empty()) return {};
  std::mt19937_64 random(seed);
  std::vector<double> estimates, sample(values.size());
  estimates.reserve(resamples);
  for (int r = 0; r < resamples; ++r) {
    for (double& value : sample) value = values[draw(random, values.size())];
    estimates.push_back(median_of(sample));
  }
  return percentile_interval(estimates, confidence);
}

std::vector<Interval> bootstrap_share_intervals(const std::vector<std::vector<int>>& positions,
                                                const std::vector<int>& holes, int methods,
                                                int position, double confidence, int resamples,
                                                std::uint64_t seed) {
  check_bootstrap(confidence, resamples);
  std::vector<int> ranked;
  for (int h : holes) {
    if (!positions.at(h).empty()) ranked.push_back(h);
  }
  std::vector<Interval> intervals(methods);
  if (ranked.empty()) return intervals;
  std::mt19937_64 random(seed);
  std::vector<std::vector<double>> estimates(methods);
  std::vector<int> counts(methods);
  for (int r = 0; r < resamples; ++r) {
    std::fill(counts.begin(), counts.end(), 0);
    for (size_t i = 0; i < ranked.size(); ++i) {
      const std::vector<int>& row = positions[ranked[draw(random, ranked.size())]];
      for (int m = 0; m < methods; ++m) counts[m] += row.at(m) == position;
    }
    for (int m = 0; m < methods; ++m) {
      estimates[m].push_back(static_cast<double>(counts[m]) / ranked.size());
    }
  }
  for (int m = 0; m < methods; ++m) intervals[m] = percentile_interval(estimates[m], confidence);
  return intervals;
}

SignedRankTest wilcoxon_signed_rank(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size()) throw InvalidInput("wilcoxon_signed_rank: samples of different sizes");
  std::vector<std::pair<double, int>> differences;  // (|x − y|, sign)
  for (size_t i = 0; i < x.size(); ++i) {
    if (std::isnan(x[i]) || std::isnan(y[i])) throw InvalidInput("wilcoxon_signed_rank: NaN");
    if (x[i] == y[i]) continue;  // +inf against +inf included
    const double difference = x[i] - y[i];
    differences.emplace_back(std::abs(difference), difference > 0 ? 1 : -1);
  }
  SignedRankTest test;
  const int n = static_cast<int>(differences.size());
  test.pairs = n;
  if (n == 0) return test;
  std::sort(differences.begin(), differences.end());
  // Mean ranks of tied |x − y|, and Σ(t³ − t) over the groups of ties for the variance.
  double positive = 0, ties = 0;
  for (int begin = 0; begin < n;) {
    int end = begin + 1;
    while (end < n && differences[end].first == differences[begin].first) ++end;
    const double rank = (begin + 1 + end) / 2.0;
    for (int i = begin; i < end; ++i) positive += differences[i].second > 0 ? rank : 0;
    const double t = end - begin;
    ties += t * t * t - t;
    begin = end;
  }
  const double total = n * (n + 1) / 2.0;
  test.statistic = std::min(positive, total - positive);
  if (n <= 50 && ties == 0) {
    // counts[s]: subsets of the ranks 1..n whose sum is s (each rank's sign is a fair coin).
    std::vector<double> counts(static_cast<size_t>(total) + 1, 0.0);
    counts[0] = 1;
    for (int rank = 1; rank <= n; ++rank) {
      for (int s = static_cast<int>(total); s >= rank; --s) counts[s] += counts[s - rank];
    }
    double below = 0;
    for (int s = 0; s <= static_cast<int>(test.statistic); ++s) below += counts[s];
    test.p = std::min(1.0, 2 * below / std::ldexp(1.0, n));
    test.exact = true;
    return test;
  }
  const double mean = total / 2;
  const double variance = n * (n + 1) * (2 * n + 1) / 24.0 - ties / 48;
  if (!(variance > 0)) return test;
  const double z = (std::abs(test.statistic - mean) - 0.5) / std::sqrt(variance);
  test.p = std::min(1.0, std::erfc(std::max(z, 0.0) / std::sqrt(2.0)));
  return test;
}

}  // namespace rangefill
