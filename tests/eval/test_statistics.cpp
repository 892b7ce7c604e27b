#include "rangefill/eval/statistics.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "rangefill/core/errors.h"

namespace rangefill {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Darwin's paired differences of cross- and self-fertilised plants (Fisher's example): W = 24, two
// sided p = 1352 / 2^15 from the exact distribution (as scipy.stats.wilcoxon gives it).
TEST(WilcoxonSignedRank, DarwinsDataHaveTheTextbookExactP) {
  const std::vector<double> d = {6, 8, 14, 16, 23, 24, 28, 29, 41, -48, 49, 56, 60, -67, 75};
  const SignedRankTest test = wilcoxon_signed_rank(d, std::vector<double>(d.size(), 0.0));
  EXPECT_EQ(test.pairs, 15);
  EXPECT_EQ(test.statistic, 24);
  EXPECT_TRUE(test.exact);
  EXPECT_DOUBLE_EQ(test.p, 0.041259765625);
  // The same pairs the other way round: the same test.
  EXPECT_DOUBLE_EQ(wilcoxon_signed_rank(std::vector<double>(d.size(), 0.0), d).p, test.p);
}

// With tied |x − y| the normal approximation stands in; on 16 pairs it stays within 0.02 of the
// exact p counted over all 2^16 sign patterns with the same mid-ranks.
TEST(WilcoxonSignedRank, TiesUseTheNormalApproximationCloseToTheCountedP) {
  const std::vector<double> d = {1, 1, 2, 2, 2, 3, 4, 4, 5, 6, 6, 7, -1, -2, -4, -6};
  const SignedRankTest test = wilcoxon_signed_rank(d, std::vector<double>(d.size(), 0.0));
  ASSERT_FALSE(test.exact);
  std::vector<double> magnitude(d.size()), rank(d.size());
  for (size_t i = 0; i < d.size(); ++i) magnitude[i] = std::abs(d[i]);
  for (size_t i = 0; i < d.size(); ++i) {
    double below = 0, equal = 0;
    for (double m : magnitude) {
      below += m < magnitude[i];
      equal += m == magnitude[i];
    }
    rank[i] = below + (equal + 1) / 2;
  }
  const double total = d.size() * (d.size() + 1) / 2.0;
  int extreme = 0;
  for (unsigned signs = 0; signs < (1u << d.size()); ++signs) {
    double positive = 0;
    for (size_t i = 0; i < d.size(); ++i) positive += (signs >> i & 1) ? rank[i] : 0;
    extreme += std::min(positive, total - positive) <= test.statistic + 1e-9;
  }
  EXPECT_NEAR(test.p, extreme / std::ldexp(1.0, static_cast<int>(d.size())), 0.02);
  EXPECT_GT(test.p, 0.01);
  EXPECT_LT(test.p, 0.2);
}

// A failure (+inf) is worse than any value: it ranks as the largest difference; two failures are
// equal and left out, as are equal values.
TEST(WilcoxonSignedRank, FailuresRankLastAndEqualPairsAreLeftOut) {
  const SignedRankTest test =
      wilcoxon_signed_rank({1, 2, kInf, kInf, 5, 6, 7, 8}, {2, 4, 1, kInf, 5, 9, 11, 13});
  EXPECT_EQ(test.pairs, 6);
  EXPECT_EQ(test.statistic, 6);  // the failure's rank 6 is the only positive one
  EXPECT_TRUE(test.exact);
  EXPECT_DOUBLE_EQ(test.p, 2 * 14 / 64.0);  // W+ ≤ 6: 14 of the 64 sign patterns of 1..6
  EXPECT_TRUE(std::isnan(wilcoxon_signed_rank({1, kInf}, {1, kInf}).p));
  EXPECT_THROW(wilcoxon_signed_rank({1}, {1, 2}), InvalidInput);
  EXPECT_THROW(wilcoxon_signed_rank({std::nan("")}, {1}), InvalidInput);
}

// The median's interval: on 400 draws of N(0, 1) it holds 0 and is about 2 × 1.96 × 1.2533 / 20 =
// 0.25 wide; the same values and seed give the same interval; constant values give a point.
TEST(BootstrapMedianInterval, CoversTheMedianWithTheWidthTheoryGives) {
  std::mt19937_64 random(7);
  std::normal_distribution<double> normal;
  std::vector<double> values(400);
  for (double& v : values) v = normal(random);
  const Interval interval = bootstrap_median_interval(values);
  EXPECT_LT(interval.low, 0);
  EXPECT_GT(interval.high, 0);
  EXPECT_GT(interval.high - interval.low, 0.15);
  EXPECT_LT(interval.high - interval.low, 0.35);
  const Interval again = bootstrap_median_interval(values);
  EXPECT_EQ(again.low, interval.low);
  EXPECT_EQ(again.high, interval.high);
  const Interval point = bootstrap_median_interval({2, 2, 2});
  EXPECT_EQ(point.low, 2);
  EXPECT_EQ(point.high, 2);
  EXPECT_TRUE(std::isnan(bootstrap_median_interval({}).low));
  EXPECT_THROW(bootstrap_median_interval({1}, 1.0), InvalidInput);
}

// Shares of first places: a method first everywhere has [1, 1]; a method first on half of 200
// holes gets an interval round 0.5 about 2 × 1.96 × 0.5 / √200 = 0.14 wide; unranked holes (empty
// rows) are left out; no ranked hole gives NaN bounds.
TEST(BootstrapShareIntervals, ShareOfFirstPlaces) {
  std::vector<std::vector<int>> positions;
  for (int h = 0; h < 200; ++h)
    positions.push_back(h % 2 ? std::vector<int>{1, 2, 1} : std::vector<int>{1, 1, 3});
  positions.push_back({});
  std::vector<int> holes(positions.size());
  for (size_t h = 0; h < holes.size(); ++h) holes[h] = static_cast<int>(h);
  const std::vector<Interval> first = bootstrap_share_intervals(positions, holes, 3);
  EXPECT_EQ(first[0].low, 1);
  EXPECT_EQ(first[0].high, 1);
  for (int m : {1, 2}) {
    EXPECT_LT(first[m].low, 0.5);
    EXPECT_GT(first[m].high, 0.5);
    EXPECT_NEAR(first[m].high - first[m].low, 0.14, 0.04);
  }
  const std::vector<Interval> none = bootstrap_share_intervals(positions, {200}, 3);
  EXPECT_TRUE(std::isnan(none[0].low));
}

}  // namespace
}  // namespace rangefill
