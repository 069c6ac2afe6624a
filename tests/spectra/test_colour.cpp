#include <gtest/gtest.h>

#include <cmath>

#include "core/text_table.h"
#include "spectra/colour.h"
#include "spectra/illuminants.h"
#include "spectra/rgb_upsampling.h"

namespace nx {
namespace {

// IEC 61966-2-1 publishes the XYZ -> sRGB matrix rounded to four decimals.
TEST(Colour, SrgbMatrixMatchesIec61966) {
  const double published[3][3] = {
      {3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
  for (int col = 0; col < 3; ++col) {
    const Xyz unit{col == 0 ? 1.0 : 0.0, col == 1 ? 1.0 : 0.0, col == 2 ? 1.0 : 0.0};
    const Rgb r = xyzToLinearSrgb(unit);
    EXPECT_NEAR(r.r, published[0][col], 6e-4);
    EXPECT_NEAR(r.g, published[1][col], 6e-4);
    EXPECT_NEAR(r.b, published[2][col], 6e-4);
  }
  const Rgb white = xyzToLinearSrgb(d65WhiteXyz());
  EXPECT_NEAR(white.r, 1.0, 1e-12);
  EXPECT_NEAR(white.g, 1.0, 1e-12);
  EXPECT_NEAR(white.b, 1.0, 1e-12);
}

TEST(Colour, SrgbTransferFunction) {
  EXPECT_NEAR(srgbEncode(0.0031308), 0.04045, 1e-5);
  EXPECT_NEAR(srgbEncode(0.5), 1.055 * std::pow(0.5, 1 / 2.4) - 0.055, 1e-15);
  EXPECT_NEAR(srgbEncode(0.5), 0.735357, 1e-6);
  EXPECT_DOUBLE_EQ(srgbEncode(1.0), 1.0);
  EXPECT_DOUBLE_EQ(srgbEncode(0.0), 0.0);
  for (double v = 0; v <= 1.0; v += 0.01) EXPECT_NEAR(srgbDecode(srgbEncode(v)), v, 1e-12);
}

// Sharma, Wu & Dalal (2005), test data for CIEDE2000, pairs 1-7, 17, 18 and 25.
TEST(Colour, DeltaE2000AgainstSharmaTestData) {
  struct Pair {
    Lab a, b;
    double de;
  };
  const Pair pairs[] = {{{50, 2.6772, -79.7751}, {50, 0, -82.7485}, 2.0425},
                        {{50, 3.1571, -77.2803}, {50, 0, -82.7485}, 2.8615},
                        {{50, 2.8361, -74.0200}, {50, 0, -82.7485}, 3.4412},
                        {{50, -1.3802, -84.2814}, {50, 0, -82.7485}, 1.0000},
                        {{50, -1.1848, -84.8006}, {50, 0, -82.7485}, 1.0000},
                        {{50, -0.9009, -85.5211}, {50, 0, -82.7485}, 1.0000},
                        {{50, 0, 0}, {50, -1, 2}, 2.3669},
                        {{50, 2.49, -0.001}, {50, -2.49, 0.0009}, 7.1792},
                        {{50, 2.49, -0.001}, {50, -2.49, 0.0010}, 7.1792},
                        {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644}};
  for (const auto& p : pairs) {
    EXPECT_NEAR(deltaE2000(p.a, p.b), p.de, 1e-4);
    EXPECT_NEAR(deltaE2000(p.b, p.a), p.de, 1e-4);
  }
}

// The ColorChecker (Ohta's measured reflectances) under D65: the library's path
// (1 nm integration, derived matrix) against a computation written out here from
// independent numbers (CIE's tabulated D65, 10 nm sums, IEC's published matrix),
// and against the chart's published sRGB values.
TEST(Colour, ColorCheckerUnderD65) {
  const NumberTable chart = readNumberTable(NX_TEST_DATA_DIR "/colorchecker_ohta_10nm.csv", true);
  // CIE 15 Table T.1, D65 at 380..780 nm every 10 nm.
  const double d65[41] = {49.9755, 54.6482, 82.7549, 91.486,  93.4318, 86.6823, 104.865,
                          117.008, 117.812, 114.861, 115.923, 108.811, 109.354, 107.802,
                          104.790, 107.689, 104.405, 104.046, 100.000, 96.3342, 95.788,
                          88.6856, 90.0062, 89.5991, 87.6987, 83.2886, 83.6992, 80.0268,
                          80.2146, 82.2778, 78.2842, 69.7213, 71.6091, 74.349,  61.604,
                          69.8856, 75.087,  63.5927, 46.4182, 66.8054, 63.3828};
  const double iec[3][3] = {
      {3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
  // Published sRGB (X-Rite, 8-bit) of the same patches, in the file's column order.
  const int published[12][3] = {{115, 82, 68},  {194, 150, 130}, {98, 122, 157},  {87, 108, 67},
                                {214, 126, 44}, {80, 91, 166},   {231, 199, 31},  {187, 86, 149},
                                {8, 133, 161},  {243, 243, 242}, {122, 122, 121}, {52, 52, 52}};
  const Spectrum d65Library = illuminantD(nominalDaylightCct(65));
  for (size_t patch = 0; patch < 12; ++patch) {
    std::vector<double> nm, r;
    double ref[3] = {0, 0, 0}, norm = 0;
    for (size_t i = 0; i < chart.rows.size(); ++i) {
      const double l = chart.rows[i].values[0], refl = chart.rows[i].values[patch + 1];
      nm.push_back(l);
      r.push_back(refl);
      const Xyz cmf = cieCmf(l);
      ref[0] += refl * d65[i] * cmf.x;
      ref[1] += refl * d65[i] * cmf.y;
      ref[2] += refl * d65[i] * cmf.z;
      norm += d65[i] * cmf.y;
    }
    int refRgb[3];
    for (int c = 0; c < 3; ++c) {
      const double lin = (iec[c][0] * ref[0] + iec[c][1] * ref[1] + iec[c][2] * ref[2]) / norm;
      const double v = lin <= 0.0031308 ? 12.92 * lin : 1.055 * std::pow(lin, 1 / 2.4) - 0.055;
      refRgb[c] = static_cast<int>(std::lround(255 * std::clamp(v, 0.0, 1.0)));
    }
    const Rgb lin =
        xyzToLinearSrgb(reflectanceToXyz(Spectrum(TabulatedSpectrum{nm, r}), d65Library));
    const int ours[3] = {int(std::lround(255 * srgbEncode(std::clamp(lin.r, 0.0, 1.0)))),
                         int(std::lround(255 * srgbEncode(std::clamp(lin.g, 0.0, 1.0)))),
                         int(std::lround(255 * srgbEncode(std::clamp(lin.b, 0.0, 1.0))))};
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(ours[c], refRgb[c], 2) << chart.header[patch + 1] << " channel " << c;
      EXPECT_NEAR(ours[c], published[patch][c], 14) << chart.header[patch + 1] << " channel " << c;
    }
  }
}

} // namespace
} // namespace nx
