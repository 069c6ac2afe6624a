#include <gtest/gtest.h>

#include "spectra/cie.h"
#include "spectra/colour.h"

namespace nx {
namespace {

TEST(Cie, IntegralOfYBarIs106_857) {
  double sum = 0;
  for (double v : cieTables().yBar) sum += v; // 1 nm spacing
  EXPECT_NEAR(sum, 106.857, 106.857 * 1e-3);
  EXPECT_NEAR(sum, kCieYIntegral, 1e-6);
}

TEST(Cie, EqualEnergyWhiteIsAtOneThird) {
  double x = 0, y = 0, z = 0;
  for (int i = 0; i < kCieSamples; ++i) {
    x += cieTables().xBar[i];
    y += cieTables().yBar[i];
    z += cieTables().zBar[i];
  }
  EXPECT_NEAR(x / (x + y + z), 1.0 / 3.0, 3e-4);
  EXPECT_NEAR(y / (x + y + z), 1.0 / 3.0, 3e-4);
}

TEST(Cie, KnownTableValuesAndInterpolation) {
  EXPECT_DOUBLE_EQ(cieCmf(555).y, 1.0);
  EXPECT_DOUBLE_EQ(cieCmf(600).x, 1.0622);
  EXPECT_DOUBLE_EQ(cieCmf(450).z, 1.77211);
  EXPECT_NEAR(cieCmf(554.5).y, 0.5 * (0.9997482 + 1.0), 1e-12);
  EXPECT_EQ(cieCmf(359.9).y, 0.0);
  EXPECT_EQ(cieCmf(830.1).x, 0.0);
  EXPECT_NEAR(cieCmf(830).x, 1.25114e-06, 1e-12);
}

TEST(Cie, FlatSpectrumOfOneHasLuminanceOne) {
  EXPECT_NEAR(spectrumToXyz(Spectrum(ConstantSpectrum{1.0})).y, 1.0, 1e-6);
  EXPECT_NEAR(spectrumToXyz(Spectrum(ConstantSpectrum{2.5})).y, 2.5, 1e-6);
}

} // namespace
} // namespace nx
