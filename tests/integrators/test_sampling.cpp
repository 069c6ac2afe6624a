#include <gtest/gtest.h>

#include <functional>

#include "core/frame.h"
#include "integrators/sampling.h"
#include "support/direction_chi_square.h"
#include "support/statistics.h"

namespace nx {
namespace {

TEST(Sampling, CosineHemisphere) {
  expectDirectionsFollowPdf(sampleCosineHemisphere,
                            [](const Vec3& w) { return cosineHemispherePdf(w.z); });
}

// The concentric disk mapping (a thin lens's aperture) is uniform: cells of equal area in
// (r^2, phi) receive equal counts.
TEST(Sampling, ConcentricDiskIsUniform) {
  const int nr = 30, nphi = 40, n = 200000;
  std::vector<double> obs(nr * nphi, 0), exp(nr * nphi, static_cast<double>(n) / (nr * nphi));
  for (int i = 0; i < n; ++i) {
    float x = 0, y = 0;
    sampleConcentricDisk(uniform2(static_cast<uint32_t>(i)), x, y);
    const double r2 = static_cast<double>(x) * x + static_cast<double>(y) * y;
    ASSERT_LE(r2, 1.0 + 1e-6);
    double phi = std::atan2(y, x);
    if (phi < 0) phi += 2 * kPi;
    const int ir = std::min(nr - 1, static_cast<int>(r2 * nr));
    const int ip = std::min(nphi - 1, static_cast<int>(phi / (2 * kPi) * nphi));
    obs[ir * nphi + ip] += 1;
  }
  const auto [stat, dof] = test::chiSquare(obs, exp);
  EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << "chi2 " << stat << " dof " << dof;
}

TEST(Sampling, UniformSphere) {
  expectDirectionsFollowPdf(sampleUniformSphere, [](const Vec3&) { return 1 / (4 * kPi); });
}

TEST(Sampling, UniformConeWideAndNarrow) {
  // (The cone edges fall on cell boundaries, so the numerical cell integrals are exact.)
  for (double cosMax : {0.3, 0.9}) {
    expectDirectionsFollowPdf(
        [&](Sample2 u) { return sampleUniformCone(u, 1 - cosMax); },
        [&](const Vec3& w) { return w.z >= cosMax ? uniformConePdf(1 - cosMax) : 0.0; });
  }
  // A narrow cone: uniform over its own (cos theta, phi) cells.
  const double narrow = 0.995;
  const int nz = 20, nphi = 20, n = 100000;
  std::vector<double> obs(nz * nphi, 0), exp(nz * nphi, n / double(nz * nphi));
  for (int i = 0; i < n; ++i) {
    const Vec3 w = sampleUniformCone(uniform2(static_cast<uint32_t>(i)), 1 - narrow);
    const int iz = std::min(nz - 1, static_cast<int>((1 - w.z) / (1 - narrow) * nz));
    const double phi = std::atan2(w.y, w.x) + kPi;
    obs[iz * nphi + std::min(nphi - 1, static_cast<int>(phi / (2 * kPi) * nphi))] += 1;
  }
  const auto [stat, dof] = test::chiSquare(obs, exp);
  EXPECT_LT(test::chiSquareZ(stat, dof), 4.0);
  // Cones of 1e-5 and 1e-10 rad (a 1-unit light 1e5 away, a 1e-5 light 1e5 away): every
  // direction inside, none degenerate, and the density finite.
  for (double sin2 : {1e-10, 1e-20}) {
    const double oneMinusCosMax = oneMinusCosFromSin2(sin2);
    EXPECT_NEAR(oneMinusCosMax, sin2 / 2 + sin2 * sin2 / 8, 1e-12 * sin2); // Taylor series
    EXPECT_TRUE(std::isfinite(uniformConePdf(oneMinusCosMax)));
    for (uint32_t i = 0; i < 1000; ++i) {
      const Vec3 w = sampleUniformCone(uniform2(i), oneMinusCosMax);
      const float sinTheta = std::sqrt(w.x * w.x + w.y * w.y);
      EXPECT_LE(sinTheta, std::sqrt(sin2) * (1 + 1e-6));
      EXPECT_NEAR(length(w), 1.0f, 1e-6f);
    }
  }
}

// 1 - cos(theta max) against a long-double reference free of cancellation, from
// hemispheres down to the tiniest cones, across the switch between the two formulas.
TEST(Sampling, OneMinusCosFromSin2IsAccurateAtEveryScale) {
  for (double e = -20; e <= 0; e += 0.01) {
    const double sin2 = std::pow(10.0, e);
    const long double ref = sin2 / (1.0L + std::sqrt(1.0L - static_cast<long double>(sin2)));
    EXPECT_NEAR(oneMinusCosFromSin2(sin2), static_cast<double>(ref),
                1e-11 * static_cast<double>(ref))
        << sin2;
  }
  EXPECT_EQ(oneMinusCosFromSin2(1.0), 1.0);
}

TEST(Sampling, PowerHeuristic) {
  EXPECT_FLOAT_EQ(powerHeuristic(1, 1), 0.5f);
  EXPECT_FLOAT_EQ(powerHeuristic(3, 1), 0.9f);
  EXPECT_FLOAT_EQ(powerHeuristic(0, 2), 0.0f);
  EXPECT_FLOAT_EQ(powerHeuristic(0, 0), 0.0f);
  EXPECT_FLOAT_EQ(powerHeuristic(INFINITY, 1), 1.0f);
  // Densities whose squares overflow a float (a tiny light very far away) stay finite.
  EXPECT_FLOAT_EQ(powerHeuristic(1e22f, 1), 1.0f);
  EXPECT_FLOAT_EQ(powerHeuristic(1, 1e22f), 0.0f);
  EXPECT_FLOAT_EQ(powerHeuristic(3e30f, 1e30f), 0.9f);
  EXPECT_FLOAT_EQ(powerHeuristic(1, INFINITY), 0.0f);
}

} // namespace
} // namespace nx
