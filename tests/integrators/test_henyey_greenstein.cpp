// The Henyey-Greenstein phase function: normalisation, mean cosine, and its sampling routine
// against its density (chi-square).

#include <gtest/gtest.h>

#include "integrators/media/henyey_greenstein.h"
#include "support/direction_chi_square.h"

namespace nx {
namespace {

// Integral over the sphere of p(cos) * cos^k, by the midpoint rule in cos theta.
double moment(float g, int k) {
  const int n = 200000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double c = -1 + 2.0 * (i + 0.5) / n;
    sum += henyeyGreenstein(static_cast<float>(c), g) * std::pow(c, k);
  }
  return sum * 2 * kPi * 2.0 / n;
}

TEST(HenyeyGreenstein, NormalisedWithMeanCosineG) {
  for (float g : {-0.9f, -0.3f, 0.0f, 0.5f, 0.95f}) {
    EXPECT_NEAR(moment(g, 0), 1.0, 2e-3) << g;
    EXPECT_NEAR(moment(g, 1), g, 2e-3) << g;
  }
  EXPECT_NEAR(henyeyGreenstein(0.3f, 0.0f), 1 / (4 * kPi), 1e-7);
}

TEST(HenyeyGreenstein, SamplingFollowsTheDensity) {
  const Vec3 dIn = normalize(Vec3(0.3f, -0.5f, 0.8f));
  for (float g : {-0.7f, 0.0f, 0.0005f, 0.3f, 0.85f}) {
    SCOPED_TRACE(g);
    expectDirectionsFollowPdf([&](Sample2 u) { return sampleHenyeyGreenstein(dIn, g, u); },
                              [&](const Vec3& w) { return henyeyGreenstein(dot(w, dIn), g); });
  }
}

TEST(HenyeyGreenstein, SampledMeanCosineIsG) {
  const Vec3 dIn(0, 0, 1);
  for (float g : {-0.5f, 0.9f}) {
    double sum = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i)
      sum += sampleHenyeyGreenstein(dIn, g, uniform2(static_cast<uint32_t>(i))).z;
    // standard error of the mean cosine is below sqrt(1/n)
    EXPECT_NEAR(sum / n, g, 4 / std::sqrt(double(n))) << g;
  }
}

} // namespace
} // namespace nx
