// The test helpers' statistics checked on synthetic data whose answer is known, so that the
// render tests built on them can fail.

#include <gtest/gtest.h>

#include <random>

#include "support/statistics.h"

namespace nx {
namespace {

// Renders simulated as means of 8 exponential draws per value with the sample variance of the
// mean as the variance channel: the ratio is 1 within its jackknife error; a channel 1.5x too
// large is told apart from that at the tolerance the render tests use (3.5 errors).
TEST(TestStatistics, VarianceScatterRatioFindsAWrongVarianceChannel) {
  std::mt19937 rng(7);
  std::exponential_distribution<double> draw(1.0);
  constexpr int kRenders = 192, kValues = 500, kSamples = 8;
  const std::vector<double> zeros(kValues, 0.0);
  std::vector<std::vector<double>> values(kRenders, zeros), variances = values, tooLarge = values;
  for (int j = 0; j < kRenders; ++j)
    for (int k = 0; k < kValues; ++k) {
      test::RunningStats s;
      for (int i = 0; i < kSamples; ++i) s.add(draw(rng) * (1 + k % 7));
      values[j][k] = s.mean;
      variances[j][k] = s.variance() / kSamples;
      tooLarge[j][k] = 1.5 * variances[j][k];
    }
  const test::VarianceScatterRatio right = test::varianceScatterRatio(values, variances);
  EXPECT_GT(right.standardError, 0.0);
  EXPECT_LT(std::abs(right.ratio - 1), 3.5 * right.standardError)
      << right.ratio << " +- " << right.standardError;
  const test::VarianceScatterRatio wrong = test::varianceScatterRatio(values, tooLarge);
  EXPECT_GT(std::abs(wrong.ratio - 1), 3.5 * wrong.standardError)
      << wrong.ratio << " +- " << wrong.standardError;
}

// Student's t tail against values from tables (and its limit, the normal): t = 2.131 is the
// two-sided 5% point of 15 degrees of freedom, 2.576 the normal's 1% point; the critical
// values of a 5-sigma test from n values fall towards 5 as n grows.
TEST(TestStatistics, StudentTailsAndCriticalValues) {
  EXPECT_NEAR(test::studentTTail(2.131, 15), 0.05, 2e-4);
  EXPECT_NEAR(test::studentTTail(12.706, 1), 0.05, 2e-4);
  EXPECT_NEAR(test::studentTTail(2.576, 100000), 0.01, 1e-4);
  EXPECT_NEAR(test::studentCritical(1.959964, 16), 2.131, 2e-3);
  EXPECT_NEAR(test::studentCritical(5, 16), 8.27, 0.02);
  EXPECT_NEAR(test::studentCritical(5, 256), 5.13, 0.01);
  EXPECT_NEAR(test::studentCritical(5, 1000000), 5.0, 1e-3);
}

} // namespace
} // namespace nx
