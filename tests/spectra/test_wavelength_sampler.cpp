#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/sampler.h"
#include "spectra/cie.h"
#include "spectra/wavelength_sampler.h"
#include "support/statistics.h"

namespace nx {
namespace {

TEST(WavelengthSampler, PdfIntegratesToOneOverAnyRange) {
  for (auto [lo, hi] : {std::pair{360.0, 830.0}, std::pair{395.0, 705.0}, std::pair{300.0, 400.0},
                        std::pair{650.0, 1000.0}}) {
    const WavelengthSampler s(lo, hi);
    double integral = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) integral += s.pdf(lo + (hi - lo) * (i + 0.5) / n) * (hi - lo) / n;
    EXPECT_NEAR(integral, 1.0, 1e-6) << lo << "-" << hi;
    EXPECT_EQ(s.pdf(lo - 1), 0.0);
    EXPECT_EQ(s.pdf(hi + 1), 0.0);
  }
}

TEST(WavelengthSampler, InverseCdfMatchesPdf) {
  const WavelengthSampler s(380, 780);
  const int bins = 80, n = 400000;
  std::vector<double> obs(bins, 0), exp(bins, 0);
  for (int i = 0; i < n; ++i) {
    const double l = s.wavelength(sampleValue(SamplerKind::Independent, i, 0, 0, 1));
    ASSERT_GE(l, 380.0);
    ASSERT_LE(l, 780.0);
    obs[std::min(bins - 1, static_cast<int>((l - 380) / 5))] += 1;
  }
  for (int b = 0; b < bins; ++b) {
    double p = 0;
    for (int k = 0; k < 100; ++k) p += s.pdf(380 + 5 * b + 5 * (k + 0.5) / 100) * 0.05;
    exp[b] = p * n;
  }
  const auto [stat, dof] = test::chiSquare(obs, exp);
  EXPECT_LT(test::chiSquareZ(stat, dof), 4.0);
}

TEST(WavelengthSampler, HeroLanesAreRotatedInPrimarySampleSpace) {
  const WavelengthSampler s(360, 830);
  const SampledWavelengths w = s.sample(0.1f);
  for (int i = 0; i < kLanes; ++i) {
    double u = 0.1 + static_cast<double>(i) / kLanes;
    if (u >= 1) u -= 1;
    EXPECT_NEAR(w.lambda[i], s.wavelength(u), 1e-3);
    EXPECT_NEAR(w.pdf[i], s.pdf(w.lambda[i]), 1e-6);
  }
}

// Two primary samples: lane i at the offset within stratum (h + i) mod kLanes, h the hero's
// stratum; one sample u is the same as (frac(kLanes u), floor(kLanes u) / kLanes).
TEST(WavelengthSampler, LanesShareOneOffsetInStrataFromTheHeros) {
  const WavelengthSampler s(360, 830);
  for (const float offset : {0.0123f, 0.3f, 0.987f}) // away from the segments' ends
    for (int h = 0; h < kLanes; ++h) {
      const float heroStratum = (static_cast<float>(h) + 0.5f) / kLanes;
      const SampledWavelengths w = s.sample(offset, heroStratum);
      for (int i = 0; i < kLanes; ++i) {
        const double u = (offset + static_cast<float>((h + i) % kLanes)) / kLanes;
        EXPECT_NEAR(w.lambda[i], s.wavelength(u), 1e-3) << offset << " " << h << " " << i;
        EXPECT_NEAR(w.pdf[i], s.pdf(w.lambda[i]), 1e-6);
      }
    }
  for (const float u : {0.0f, 0.1f, 0.37f, 0.8f}) {
    const SampledWavelengths a = s.sample(u);
    const float scaled = u * kLanes;
    const SampledWavelengths b = s.sample(scaled - std::floor(scaled), std::floor(scaled) / kLanes);
    for (int i = 0; i < kLanes; ++i) EXPECT_EQ(a.lambda[i], b.lambda[i]) << u;
  }
}

// Every lane's wavelength follows the density when the offset and the hero's stratum come from
// one scrambled Sobol pair, as in the renderer (chi-square of each lane's primary sample,
// recovered from its wavelength, over 64 equal-probability bins).
TEST(WavelengthSampler, LanesFromASobolPairFollowTheDensity) {
  const WavelengthSampler s(380, 780);
  constexpr int kBinsOfU = 64;
  for (int lane : {0, kLanes - 1}) {
    std::vector<double> observed(kBinsOfU, 0.0), expected(kBinsOfU, 0.0);
    constexpr uint32_t kPixels = 4000, kSamples = 8;
    for (uint32_t p = 0; p < kPixels; ++p) {
      const PixelSequence sequence(SamplerKind::SobolOwen, p, 3);
      for (uint32_t i = 0; i < kSamples; ++i) {
        const Sample2 u = sequence.pair(sequence.sample(i), 0);
        const float nm = s.sample(u.u, u.v).lambda[lane];
        // The bin of the wavelength's CDF value: the first knot of j / kBinsOfU above it.
        int bin = 0;
        while (bin + 1 < kBinsOfU && s.wavelength(static_cast<double>(bin + 1) / kBinsOfU) <= nm)
          ++bin;
        observed[static_cast<size_t>(bin)] += 1;
      }
    }
    for (double& e : expected) e = static_cast<double>(kPixels * kSamples) / kBinsOfU;
    const auto [stat, dof] = test::chiSquare(observed, expected);
    EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << "lane " << lane;
  }
}

// The lanes agree with the inverse CDF and carry the density of the segment they fall in:
// the smooth visible density averaged over the segment (closed form through its CDF).
TEST(WavelengthSampler, LanesMatchInverseCdfOverTheBandRange) {
  for (auto [lo, hi] : {std::pair{300.0, 1000.0}, std::pair{360.0, 830.0}}) {
    const WavelengthSampler s(lo, hi);
    const double k = 0.0072, range = std::tanh(k * (hi - 538)) - std::tanh(k * (lo - 538));
    for (int i = 0; i <= 4000; ++i) {
      const float u = std::min(static_cast<float>(i) / 4000.0f, 0x1.fffffep-1f);
      const SampledWavelengths w = s.sample(u);
      ASSERT_NEAR(w.lambda[0], s.wavelength(u), 1e-3) << lo << "-" << hi << " u " << u;
      const double x = u * WavelengthSampler::kSegments;
      if (std::abs(x - std::round(x)) > 1e-3) { // away from segment ends (rounding picks a side)
        ASSERT_EQ(w.pdf[0], static_cast<float>(s.pdf(w.lambda[0]))) << "u " << u;
      }
      const int j = std::min(static_cast<int>(x), WavelengthSampler::kSegments - 1);
      const double a = s.wavelength(static_cast<double>(j) / WavelengthSampler::kSegments),
                   b = s.wavelength(static_cast<double>(j + 1) / WavelengthSampler::kSegments);
      const double average =
          (std::tanh(k * (b - 538)) - std::tanh(k * (a - 538))) / range / (b - a);
      ASSERT_NEAR(w.pdf[0], average, 1e-4 * average) << "u " << u;
    }
  }
}

// The lane-weighted estimator of the integral of y-bar converges to 106.857 (z-test).
TEST(WavelengthSampler, ImportanceSampledIntegralOfYBar) {
  for (auto [lo, hi] : {std::pair{360.0, 830.0}, std::pair{400.0, 700.0}}) {
    const WavelengthSampler s(lo, hi);
    double exact = 0;
    for (int nm = static_cast<int>(lo); nm <= static_cast<int>(hi); ++nm) exact += cieCmf(nm).y;
    exact -= 0.5 * (cieCmf(lo).y + cieCmf(hi).y); // trapezoid ends
    test::RunningStats stats;
    for (uint32_t i = 0; i < 200000; ++i) {
      const SampledWavelengths w = s.sample(sampleValue(SamplerKind::Independent, i, 0, 0, 7));
      double est = 0;
      for (int k = 0; k < kLanes; ++k)
        est += cieCmf(w.lambda[k]).y * WavelengthSampler::laneWeight(w, k);
      stats.add(est);
    }
    EXPECT_LT(std::abs(stats.mean - exact), 4 * stats.standardError()) << lo << "-" << hi;
    EXPECT_LT(stats.standardError() / exact, 1e-3);
    if (lo == 360.0) {
      EXPECT_NEAR(exact, 106.857, 0.02);
    }
  }
}

TEST(WavelengthSampler, RejectsBadRanges) {
  EXPECT_THROW(WavelengthSampler(500, 400), Error);
  EXPECT_THROW(WavelengthSampler(0, 400), Error);
  EXPECT_THROW(WavelengthSampler(400, INFINITY), Error);
}

} // namespace
} // namespace nx

namespace nx {
namespace {

// The sensor density is a density (integrates to 1 over the traced range), its samples follow
// it (chi-square over 2 nm bins), and it keeps mass over the whole CIE range (XYZ stays
// unbiased) and over every band.
TEST(WavelengthSampler, SensorDensityIsSampledAsItsPdfSays) {
  for (const char* spec :
       {"400:700:10", "405:995:10", "gaussian:450,550,870@20,10,40", "boxes:320-340,1000-1100"}) {
    const Sensor sensor = Sensor::parse(spec);
    const double lo = std::min(sensor.minNm(), 360.0), hi = std::max(sensor.maxNm(), 830.0);
    const WavelengthSampler s = WavelengthSampler::forSensor(sensor, lo, hi);
    double integral = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) integral += s.pdf(lo + (hi - lo) * (i + 0.5) / n) * (hi - lo) / n;
    EXPECT_NEAR(integral, 1.0, 1e-5) << spec;
    for (double nm = 360; nm <= 830; nm += 1) ASSERT_GT(s.pdf(nm), 0.0) << spec << " " << nm;
    for (int b = 0; b < sensor.count(); ++b)
      EXPECT_GT(s.pdf(sensor.centroid(b)), 0.0) << spec << " band " << b;
    const int bins = static_cast<int>((hi - lo) / 2), draws = 400000;
    std::vector<double> obs(static_cast<size_t>(bins), 0), exp(static_cast<size_t>(bins), 0);
    for (int i = 0; i < draws; ++i) {
      const double l = s.wavelength(sampleValue(SamplerKind::Independent, i, 0, 0, 7));
      obs[static_cast<size_t>(std::min(bins - 1, static_cast<int>((l - lo) / 2)))] += 1;
    }
    for (int b = 0; b < bins; ++b) {
      double p = 0;
      for (int k = 0; k < 200; ++k) p += s.pdf(lo + 2 * b + 2 * (k + 0.5) / 200) * 0.01;
      exp[static_cast<size_t>(b)] = p * draws;
    }
    const auto [stat, dof] = test::chiSquare(obs, exp);
    EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << spec;
  }
}

} // namespace
} // namespace nx
