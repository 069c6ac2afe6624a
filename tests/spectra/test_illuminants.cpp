#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/math_util.h"
#include "spectra/colour.h"
#include "spectra/illuminants.h"

namespace nx {
namespace {

void expectChromaticity(const Spectrum& s, double x, double y, double tol, const char* name) {
  const Xyz c = spectrumToXyz(s);
  EXPECT_NEAR(chromaticityX(c), x, tol) << name;
  EXPECT_NEAR(chromaticityY(c), y, tol) << name;
}

TEST(Planck, RadianceAt483nm6000K) {
  // 3.1849e13 W m^-3 sr^-1 = 3.1849e4 W m^-2 sr^-1 nm^-1.
  EXPECT_NEAR(BlackbodySpectrum{6000}(483.0) * 1e9, 3.1849e13, 3.1849e13 * 1e-3);
}

TEST(Planck, WienPeakAndStefanBoltzmann) {
  for (double t : {2856.0, 5000.0, 6504.0}) {
    const BlackbodySpectrum b{t};
    double best = 0, bestNm = 0;
    for (double nm = 100; nm < 3000; nm += 0.01)
      if (b(nm) > best) best = b(nm), bestNm = nm;
    EXPECT_NEAR(bestNm, 2.897771955e-3 / t * 1e9, 0.02) << t;
    // pi * integral of B over wavelength = sigma T^4 (log-spaced midpoint rule).
    double integral = 0;
    const int n = 200000;
    const double lo = std::log(10.0), hi = std::log(1e6);
    for (int i = 0; i < n; ++i) {
      const double a = std::exp(lo + (hi - lo) * i / n), c = std::exp(lo + (hi - lo) * (i + 1) / n);
      integral += b(std::sqrt(a * c)) * (c - a);
    }
    EXPECT_NEAR(kPi * integral, 5.670374419e-8 * std::pow(t, 4),
                5.670374419e-8 * std::pow(t, 4) * 1e-4);
  }
}

TEST(Illuminants, Chromaticities) {
  expectChromaticity(*namedEmission("D65"), 0.3127, 0.3290, 5e-4, "D65");
  expectChromaticity(*namedEmission("D50"), 0.3457, 0.3585, 5e-4, "D50");
  expectChromaticity(*namedEmission("D55"), 0.3324, 0.3474, 5e-4, "D55");
  expectChromaticity(*namedEmission("D75"), 0.2990, 0.3149, 5e-4, "D75");
  expectChromaticity(*namedEmission("A"), 0.4476, 0.4074, 5e-4, "A");
  expectChromaticity(*namedEmission("E"), 1.0 / 3, 1.0 / 3, 5e-4, "E");
  expectChromaticity(*namedEmission("F1"), 0.3131, 0.3373, 5e-4, "F1");
  expectChromaticity(*namedEmission("F2"), 0.3721, 0.3751, 5e-4, "F2");
  expectChromaticity(*namedEmission("F7"), 0.3129, 0.3292, 5e-4, "F7");
  expectChromaticity(*namedEmission("F11"), 0.3805, 0.3769, 5e-4, "F11");
}

// D65 built from S0/S1/S2 equals the CIE's own D65 table (CIE 15:2004 Table T.1 values).
TEST(Illuminants, D65FromBasisMatchesTheCieTable) {
  const Spectrum d65 = illuminantD(nominalDaylightCct(65));
  const std::pair<double, double> table[] = {
      {300, 0.0341},  {380, 49.9755}, {400, 82.7549}, {460, 117.812}, {500, 109.354}, {560, 100.0},
      {600, 90.0062}, {655, 80.1207}, {700, 71.6091}, {760, 46.4182}, {780, 63.3828}};
  for (auto [nm, v] : table) EXPECT_NEAR(d65(nm), v, std::max(0.02, v * 2e-4)) << nm;
  // D50 and D75 likewise (colour-science's copy of CIE 15 tables).
  EXPECT_NEAR(illuminantD(nominalDaylightCct(50))(450), 87.247, 0.02);
  EXPECT_NEAR(illuminantD(nominalDaylightCct(75))(450), 133.010, 0.03);
}

TEST(Illuminants, DaylightAtAnyCct) {
  // Daylight chromaticity lies on the CIE daylight locus y = -3 x^2 + 2.87 x - 0.275.
  for (double t : {4000.0, 5500.0, 7000.0, 9000.0, 20000.0}) {
    const Xyz c = spectrumToXyz(illuminantD(t));
    const double x = chromaticityX(c), y = chromaticityY(c);
    EXPECT_NEAR(y, -3.0 * x * x + 2.87 * x - 0.275, 1.5e-3) << t;
  }
  EXPECT_THROW(illuminantD(3000), Error);
  EXPECT_THROW(*namedEmission("daylight:30000"), Error);
  EXPECT_TRUE(namedEmission("daylight:6000").has_value());
}

TEST(Illuminants, NiixtracerBlackbodiesAreNormalisedPlanck) {
  const Spectrum bb = *namedEmission("bbd65");
  const BlackbodySpectrum planck{6504};
  EXPECT_NEAR(bb(450) / bb(600), planck(450) / planck(600), 1e-12);
  EXPECT_NEAR(relativeLuminance(bb), 1.0, 1e-9);
  const Spectrum bba = *namedEmission("bba");
  EXPECT_NEAR(bba(700) / bba(400), BlackbodySpectrum{2856}(700) / BlackbodySpectrum{2856}(400),
              1e-9);
  expectChromaticity(*namedEmission("blackbody:2856"), 0.4476, 0.4074, 1e-3, "Planck 2856 K ~ A");
}

TEST(Illuminants, EveryNameHasLuminanceOneExceptBlackLight) {
  for (const char* n : {"A", "D50", "D55", "D65", "D75", "D93", "E", "F1", "F6", "F12", "bba",
                        "bbd50", "bbd55", "bbd65", "bbd75", "blackbody:3000", "daylight:6000"})
    EXPECT_NEAR(relativeLuminance(*namedEmission(n)), 1.0, 1e-9) << n;
  const Spectrum bl = *namedEmission("bl");
  double radiance = 0;
  for (int nm = 360; nm <= 830; ++nm) radiance += bl(nm);
  EXPECT_NEAR(radiance, 471.0, 1e-6);
  // Mostly ultraviolet: its peak is the 368 nm line, the 404.7 nm line is weaker.
  EXPECT_GT(bl(368), 2.5 * bl(404.7));
  EXPECT_GT(bl(404.7), 3 * bl(390));
  EXPECT_LT(relativeLuminance(bl), 0.05);
}

TEST(Illuminants, UnknownAndMalformedNames) {
  EXPECT_FALSE(namedEmission("D6").has_value());
  EXPECT_FALSE(namedEmission("F13").has_value());
  EXPECT_FALSE(namedEmission("d65").has_value());
  EXPECT_FALSE(namedEmission("gray").has_value());
  EXPECT_THROW(*namedEmission("blackbody:hot"), Error);
  EXPECT_THROW(*namedEmission("blackbody:-5"), Error);
}

} // namespace
} // namespace nx
