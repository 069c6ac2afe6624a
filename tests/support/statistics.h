#pragma once
// Statistical helpers for tests: chi-square goodness of fit and z-scores.

#include <cmath>
#include <vector>

namespace nx::test {

/// Pearson's chi-square statistic over the cells; cells whose expected count is below 5 are
/// pooled into one cell (the usual validity condition). Returns {statistic, degrees of freedom}.
inline std::pair<double, int> chiSquare(const std::vector<double>& observed,
                                        const std::vector<double>& expected) {
  double stat = 0, pooledObs = 0, pooledExp = 0;
  int cells = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < 5.0) {
      pooledObs += observed[i];
      pooledExp += expected[i];
      continue;
    }
    stat += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++cells;
  }
  if (pooledExp >= 5.0) {
    stat += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp;
    ++cells;
  } else if (pooledObs > 0 && pooledExp == 0) {
    stat = INFINITY; // samples where the density is zero
  }
  return {stat, cells - 1};
}

/// Upper-tail z-score of a chi-square statistic (Wilson-Hilferty cube-root approximation,
/// accurate for the tens to thousands of degrees of freedom used here). z > 4 means
/// p < 3e-5: the tests reject there, so a correct implementation fails about never.
inline double chiSquareZ(double stat, int dof) {
  const double k = dof;
  return (std::cbrt(stat / k) - (1.0 - 2.0 / (9.0 * k))) / std::sqrt(2.0 / (9.0 * k));
}

/// Running mean and variance (Welford).
struct RunningStats {
  double n = 0, mean = 0, m2 = 0;
  void add(double x) {
    n += 1;
    const double d = x - mean;
    mean += d / n;
    m2 += d * (x - mean);
  }
  double variance() const { return n > 1 ? m2 / (n - 1) : 0.0; }
  /// Standard error of the mean.
  double standardError() const { return std::sqrt(variance() / n); }
};

} // namespace nx::test
