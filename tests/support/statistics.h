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

/// Two-sided tail P(|T| > t) of Student's t distribution with `dof` degrees of freedom (t > 0):
/// the density's integral beyond t, with x = 1 / y so that the range is finite, by Simpson's
/// rule (relative error below 1e-6 for the quantiles used here).
inline double studentTTail(double t, int dof) {
  const double nu = dof;
  const double c = std::exp(std::lgamma((nu + 1) / 2) - std::lgamma(nu / 2)) / std::sqrt(nu * M_PI);
  // f(1 / y) / y^2 = c nu^((nu+1)/2) y^(nu-1) (nu y^2 + 1)^(-(nu+1)/2), log-evaluated.
  auto g = [&](double y) {
    if (y <= 0) return dof == 1 ? c : 0.0;
    return c * std::exp((nu + 1) / 2 * std::log(nu) + (nu - 1) * std::log(y) -
                        (nu + 1) / 2 * std::log(nu * y * y + 1));
  };
  constexpr int kIntervals = 2000; // even
  const double h = 1 / t / kIntervals;
  double sum = g(0) + g(1 / t);
  for (int i = 1; i < kIntervals; ++i) sum += (i % 2 ? 4 : 2) * g(i * h);
  return 2 * sum * h / 3;
}

/// The critical value of a z-test whose standard error is estimated from n values: the t
/// (n - 1 degrees of freedom) with the two-sided tail of a normal's `z` standard errors.
/// With a standard error from few values it lies far above z (n = 16: 8.3 for z = 5; n = 64:
/// 5.6; n = 256: 5.1), since the estimated error is then itself uncertain.
inline double studentCritical(double z, int n) {
  const double tail = std::erfc(z / std::sqrt(2.0));
  double lo = z, hi = 1e4;
  for (int i = 0; i < 80; ++i) {
    const double mid = std::sqrt(lo * hi);
    (studentTTail(mid, n - 1) > tail ? lo : hi) = mid;
  }
  return lo;
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

/// Variance channels against the scatter over independent renders (seeds): the ratio of the
/// mean estimated variance to the sample variance across the renders, each pooled over all
/// values (pixels x bands), with its jackknife standard error over the renders (Efron and
/// Stein 1981: leave one render out, sqrt((n - 1) / n * sum (r_j - mean r)^2)). The renders
/// are the independent units; pooled variances of path-traced images are dominated by rare
/// bright samples, so the spread of the ratio must come from the renders themselves, not from
/// a normal approximation per value.
struct VarianceScatterRatio {
  double ratio = 0;         ///< sum of mean estimated variances / sum of scatters
  double standardError = 0; ///< its jackknife standard error
};

/// `values[j][k]` and `variances[j][k]`: render j's value k and its variance channel
/// (at least three renders, all of the same size).
inline VarianceScatterRatio
varianceScatterRatio(const std::vector<std::vector<double>>& values,
                     const std::vector<std::vector<double>>& variances) {
  const size_t n = values.size(), m = values.front().size();
  const double nd = static_cast<double>(n);
  // Per value: mean and centred sum of squares over the renders, and the summed variance
  // channel; leaving render j out removes its value (Welford's update run backwards), so each
  // leave-one-out ratio costs O(values).
  std::vector<double> mean(m, 0.0), m2(m, 0.0), estimatedSum(m, 0.0);
  for (size_t k = 0; k < m; ++k) {
    for (size_t j = 0; j < n; ++j) mean[k] += values[j][k] / nd;
    for (size_t j = 0; j < n; ++j) {
      m2[k] += (values[j][k] - mean[k]) * (values[j][k] - mean[k]);
      estimatedSum[k] += variances[j][k];
    }
  }
  auto ratioWithout = [&](size_t skip) {
    double scatter = 0, estimated = 0;
    for (size_t k = 0; k < m; ++k) {
      if (skip >= n) {
        scatter += m2[k] / (nd - 1);
        estimated += estimatedSum[k] / nd;
        continue;
      }
      const double d = values[skip][k] - mean[k];
      scatter += (m2[k] - d * d * nd / (nd - 1)) / (nd - 2);
      estimated += (estimatedSum[k] - variances[skip][k]) / (nd - 1);
    }
    return estimated / scatter;
  };
  VarianceScatterRatio r;
  r.ratio = ratioWithout(n);
  RunningStats left;
  for (size_t j = 0; j < n; ++j) left.add(ratioWithout(j));
  r.standardError = std::sqrt((nd - 1) / nd * left.m2);
  return r;
}

} // namespace nx::test
