// The built-in ColorChecker: its measured spectra reproduce the chart's published colours, and
// agree with the independent 12-patch table of the test data.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>

#include "core/text_table.h"
#include "spectra/colorchecker.h"
#include "spectra/colour.h"
#include "spectra/illuminants.h"

namespace nx {
namespace {

// X-Rite's published sRGB values of the ColorChecker Classic (8-bit, D65), chart order.
constexpr std::array<std::array<int, 3>, 24> kPublishedSrgb{{
    {115, 82, 68},   {194, 150, 130}, {98, 122, 157}, {87, 108, 67},   {133, 128, 177},
    {103, 189, 170}, {214, 126, 44},  {80, 91, 166},  {193, 90, 99},   {94, 60, 108},
    {157, 188, 64},  {224, 163, 46},  {56, 61, 150},  {70, 148, 73},   {175, 54, 60},
    {231, 199, 31},  {187, 86, 149},  {8, 133, 161},  {243, 243, 242}, {200, 200, 200},
    {160, 160, 160}, {122, 122, 121}, {85, 85, 85},   {52, 52, 52},
}};

// Each patch's colour under D65 (CIELAB of the measured spectrum) lies within a few Delta E
// 2000 of the chart's published colour: a transcription error (a wrong digit, a shifted column)
// would stand out; the remaining differences are those between charts and measurements.
TEST(ColorChecker, PatchesReproduceThePublishedColours) {
  ASSERT_EQ(colorCheckerPatchNames().size(), 24u);
  const Spectrum d65 = illuminantD(nominalDaylightCct(65));
  const Xyz white = d65WhiteXyz();
  double worst = 0, sum = 0;
  for (int i = 0; i < 24; ++i) {
    const Xyz measured = reflectanceToXyz(colorCheckerPatch(i), d65);
    const auto& p = kPublishedSrgb[static_cast<size_t>(i)];
    const Xyz published = linearSrgbToXyz(
        {srgbDecode(p[0] / 255.0), srgbDecode(p[1] / 255.0), srgbDecode(p[2] / 255.0)});
    const double de = deltaE2000(xyzToLab(measured, white), xyzToLab(published, white));
    std::printf("%-14s Delta E 2000 %.2f\n",
                colorCheckerPatchNames()[static_cast<size_t>(i)].c_str(), de);
    EXPECT_LT(de, 4.0) << colorCheckerPatchNames()[static_cast<size_t>(i)];
    worst = std::max(worst, de);
    sum += de;
  }
  EXPECT_LT(sum / 24, 2.0);
  std::printf("mean %.2f, worst %.2f\n", sum / 24, worst);
}

// The 12 patches of the test data's separately kept table equal the built-in ones.
TEST(ColorChecker, AgreesWithTheTwelvePatchTestTable) {
  const NumberTable t = readNumberTable(NX_TEST_DATA_DIR "/colorchecker_ohta_10nm.csv", true);
  int compared = 0;
  for (size_t c = 1; c < t.header.size(); ++c) {
    const auto patch = colorCheckerPatch(t.header[c]);
    ASSERT_TRUE(patch) << t.header[c];
    for (const auto& row : t.rows) {
      EXPECT_DOUBLE_EQ((*patch)(row.values[0]), row.values[c]) << t.header[c];
      ++compared;
    }
  }
  EXPECT_EQ(compared, 12 * 41);
  EXPECT_FALSE(colorCheckerPatch("teal"));
}

} // namespace
} // namespace nx
