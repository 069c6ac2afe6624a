#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "integrators/ior_model.h"

namespace nx {
namespace {

// Smallest and largest n over [lo, hi] by a scan every `step` nm (NaN if any value is NaN).
std::pair<double, double> scan(const IorModel& m, double lo, double hi, double step) {
  double mn = INFINITY, mx = -INFINITY;
  for (double nm = lo; nm <= hi; nm += step) {
    const double n = m.at(nm);
    if (!std::isfinite(n)) return {NAN, NAN};
    mn = std::min(mn, n), mx = std::max(mx, n);
  }
  return {mn, mx};
}

TEST(IorModel, BuiltInGlassesStayWithinRangeOverTheTracedRange) {
  for (const char* name : {"bk7", "diamond", "fused_silica"}) {
    IorModel m;
    ASSERT_TRUE(namedGlass(name, m));
    EXPECT_FALSE(iorOutsideRange(m, 300, 1000, 1, 10).has_value()) << name;
  }
  EXPECT_FALSE(iorOutsideRange(IorModel::constant(1.5), 300, 1000, 1, 10).has_value());
  EXPECT_TRUE(iorOutsideRange(IorModel::constant(0.9), 300, 1000, 1, 10).has_value());
}

TEST(IorModel, UnknownGlassNameIsRefused) {
  IorModel m;
  EXPECT_FALSE(namedGlass("crown", m));
}

// A Sellmeier pole inside the range is found exactly, even between whole nanometres.
TEST(IorModel, SellmeierPoleBetweenWholeNanometresIsFound) {
  const IorModel m{IorModel::Kind::Sellmeier, {1, 0, 0, 0.5005 * 0.5005, 0, 0}};
  const auto nm = iorOutsideRange(m, 300, 1000, 1, 10);
  ASSERT_TRUE(nm.has_value());
  EXPECT_NEAR(*nm, 500.5, 1e-9);
}

// Random Cauchy and Sellmeier indices (Sellmeier poles kept outside the range): the exact
// verdict agrees with a 0.01 nm scan wherever the scan is not within 1e-6 of a limit, and a
// returned wavelength is outside the limits.
TEST(IorModel, ExactVerdictAgreesWithAFineScan) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  int refused = 0, accepted = 0;
  for (int i = 0; i < 300; ++i) {
    IorModel m;
    if (i % 2 == 0) {
      m.kind = IorModel::Kind::Cauchy;
      m.c = {0.95 + 0.2 * u(rng), 0.04 * (u(rng) - 0.3), 0.004 * (u(rng) - 0.5), 0, 0, 0};
    } else {
      // A UV pole (below 300 nm) and an IR pole (beyond 1000 nm); B of either sign, so that
      // n^2 - 1 is a sum of a decreasing and an increasing term with a minimum inside.
      m.kind = IorModel::Kind::Sellmeier;
      m.c = {0.6 * u(rng),  -0.6 * u(rng),    0.2 * (u(rng) - 0.5),
             0.07 * u(rng), 1.1 + 3 * u(rng), 0.001 * u(rng)};
    }
    const auto [mn, mx] = scan(m, 300, 1000, 0.01);
    const auto verdict = iorOutsideRange(m, 300, 1000, 1.0, 10.0);
    if (verdict) {
      const double n = m.at(*verdict);
      EXPECT_FALSE(std::isfinite(n) && n >= 1.0 && n <= 10.0) << i;
    }
    if (std::isnan(mn)) continue;
    if (std::abs(mn - 1.0) < 1e-6 || std::abs(mx - 10.0) < 1e-6) continue;
    const bool scanOutside = mn < 1.0 || mx > 10.0;
    EXPECT_EQ(verdict.has_value(), scanOutside) << "case " << i << " scan min " << mn;
    (scanOutside ? refused : accepted)++;
  }
  // Both verdicts occur (the test has power).
  EXPECT_GT(refused, 20);
  EXPECT_GT(accepted, 20);
}

} // namespace
} // namespace nx
