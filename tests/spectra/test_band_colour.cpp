// Colour of band values and sensors named by wavelengths.

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "spectra/band_colour.h"

namespace nx {
namespace {

TEST(BandColour, LinearInTheBandsAndExactForLinearSpectra) {
  // A spectrum linear in the wavelength is reproduced exactly by its samples, so the band
  // colour equals the colour of the spectrum itself (between the outer bands).
  std::vector<double> nm;
  for (double w = 360; w <= 830; w += 10) nm.push_back(w);
  std::vector<float> v;
  for (double w : nm) v.push_back(static_cast<float>(0.2 + 0.001 * (w - 360)));
  const Xyz got = BandColour(nm).xyz(v.data());
  const Xyz want = spectrumToXyz(Spectrum(TabulatedSpectrum{{360, 830}, {0.2, 0.2 + 0.47}, false}));
  EXPECT_NEAR(got.x, want.x, 1e-6 * want.x);
  EXPECT_NEAR(got.y, want.y, 1e-6 * want.y);
  EXPECT_NEAR(got.z, want.z, 1e-6 * want.z);
  // linearity: twice the values, twice the colour
  for (float& x : v) x *= 2;
  EXPECT_NEAR(BandColour(nm).xyz(v.data()).y, 2 * want.y, 1e-6 * want.y);
}

TEST(BandColour, FillClampsNegativeRgb) {
  const BandColour colour({450, 550, 650});
  std::vector<float> xyz, rgb;
  colour.fill({1, 0, 0, 0, 0, 1}, xyz, rgb); // a blue-only and a red-only pixel
  ASSERT_EQ(rgb.size(), 6u);
  for (float c : rgb) EXPECT_GE(c, 0.0f);
  EXPECT_GT(xyz[2], xyz[0]); // the blue pixel: Z above X
}

TEST(SensorAtWavelengths, UniformBoxesOrGaussians) {
  const Sensor u = sensorAtWavelengths({400, 410, 420, 430}, "test");
  EXPECT_TRUE(u.uniformBoxes());
  EXPECT_EQ(u.toString(), "400:430:10");
  const Sensor g = sensorAtWavelengths({450, 500, 520, 600}, "test");
  EXPECT_FALSE(g.uniformBoxes());
  ASSERT_EQ(g.count(), 4);
  EXPECT_NEAR(g.centroid(1), 500, 1e-6);
  EXPECT_NEAR(g.fwhm(1), 35, 1e-9);
  EXPECT_NEAR(g.fwhm(3), 80, 1e-9);
  EXPECT_THROW(sensorAtWavelengths({500, 500}, "test"), Error);
  EXPECT_THROW(sensorAtWavelengths({}, "test"), Error);
}

} // namespace
} // namespace nx
