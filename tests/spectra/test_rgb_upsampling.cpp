#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "spectra/colour.h"
#include "spectra/rgb_upsampling.h"

namespace nx {
namespace {

double roundTripDeltaE(const Rgb& linear) {
  const Spectrum s = upsampleSrgbReflectance(linear);
  const Rgb back = reflectanceToLinearSrgb(s);
  const Xyz white = d65WhiteXyz();
  return deltaE2000(xyzToLab(linearSrgbToXyz(linear), white),
                    xyzToLab(linearSrgbToXyz(back), white));
}

// Every colour of a 9x9x9 grid of encoded sRGB values (corners and edges of the gamut
// included) comes back from its spectrum within Delta E 2000 < 1 under D65.
TEST(RgbUpsampling, GridRoundTripBelowOneDeltaE) {
  double worst = 0;
  Rgb worstColour;
  for (int r = 0; r <= 8; ++r)
    for (int g = 0; g <= 8; ++g)
      for (int b = 0; b <= 8; ++b) {
        const Rgb lin{srgbDecode(r / 8.0), srgbDecode(g / 8.0), srgbDecode(b / 8.0)};
        const double de = roundTripDeltaE(lin);
        if (de > worst) worst = de, worstColour = lin;
      }
  EXPECT_LT(worst, 1.0) << "worst colour " << worstColour.r << " " << worstColour.g << " "
                        << worstColour.b;
  std::printf("worst round-trip Delta E 2000 on the grid: %.4f\n", worst);
}

TEST(RgbUpsampling, SpectraAreSmoothBoundedReflectances) {
  for (const Rgb c :
       {Rgb{1, 0, 0}, Rgb{0, 1, 0}, Rgb{0, 0, 1}, Rgb{0.2, 0.5, 0.1}, Rgb{0.9, 0.9, 0.1}}) {
    const Spectrum s = upsampleSrgbReflectance(c);
    for (double nm = 360; nm <= 830; nm += 1) {
      EXPECT_GE(s(nm), 0.0);
      EXPECT_LE(s(nm), 1.0);
    }
  }
  EXPECT_TRUE(upsampleSrgbReflectance({0, 0, 0}).isConstant());
  EXPECT_DOUBLE_EQ(upsampleSrgbReflectance({1, 1, 1})(500), 1.0);
  // A grey is (close to) flat.
  const Spectrum grey = upsampleSrgbReflectance({0.18, 0.18, 0.18});
  EXPECT_NEAR(grey(400), grey(700), 0.01);
  EXPECT_NEAR(grey(550), 0.18, 0.01);
}

TEST(RgbUpsampling, RejectsOutOfRangeChannels) {
  EXPECT_THROW(upsampleSrgbReflectance({1.5, 0, 0}), Error);
  EXPECT_THROW(upsampleSrgbReflectance({-0.1, 0, 0}), Error);
  EXPECT_THROW(upsampleSrgbReflectance(Rgb{NAN, 0, 0}), Error);
}

} // namespace
} // namespace nx
