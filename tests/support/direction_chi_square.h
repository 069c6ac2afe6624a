#pragma once
// Chi-square tests of direction sampling routines against their densities over the sphere.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "core/math_util.h"
#include "core/sampler.h"
#include "core/vec3.h"
#include "support/statistics.h"

namespace nx {

/// The i-th point of an independent 2D sequence (fixed seed).
inline Sample2 uniform2(uint32_t i) {
  return samplePair(SamplerKind::Independent, i, 0, 0, 99);
}

/// Chi-square of sampled directions against a density over the sphere, in (cos theta, phi)
/// cells of equal area; the expected count per cell integrates the pdf numerically. A sample
/// may fail (return the zero vector: absorbed); the density then integrates to less than 1.
inline void expectDirectionsFollowPdf(const std::function<Vec3(Sample2)>& sample,
                                      const std::function<double(const Vec3&)>& pdf,
                                      int n = 200000) {
  const int nz = 40, nphi = 40;
  std::vector<double> obs(nz * nphi, 0), exp(nz * nphi, 0);
  for (int i = 0; i < n; ++i) {
    const Vec3 w = sample(uniform2(static_cast<uint32_t>(i)));
    if (w.x == 0 && w.y == 0 && w.z == 0) continue;
    ASSERT_NEAR(length(w), 1.0f, 1e-5f);
    const int iz = std::min(nz - 1, static_cast<int>((w.z + 1) / 2 * nz));
    double phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * kPi;
    const int ip = std::min(nphi - 1, static_cast<int>(phi / (2 * kPi) * nphi));
    obs[iz * nphi + ip] += 1;
  }
  const int sub = 8;
  for (int iz = 0; iz < nz; ++iz)
    for (int ip = 0; ip < nphi; ++ip) {
      double p = 0;
      for (int a = 0; a < sub; ++a)
        for (int b = 0; b < sub; ++b) {
          const double z = -1 + 2.0 * (iz + (a + 0.5) / sub) / nz;
          const double phi = 2 * kPi * (ip + (b + 0.5) / sub) / nphi;
          const double r = std::sqrt(std::max(0.0, 1 - z * z));
          p += pdf(Vec3(static_cast<float>(r * std::cos(phi)),
                        static_cast<float>(r * std::sin(phi)), static_cast<float>(z)));
        }
      exp[iz * nphi + ip] = p / (sub * sub) * (4 * kPi / (nz * nphi)) * n;
    }
  const auto [stat, dof] = test::chiSquare(obs, exp);
  EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << "chi2 " << stat << " dof " << dof;
}

} // namespace nx
