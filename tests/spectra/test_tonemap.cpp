#include <gtest/gtest.h>

#include <cmath>

#include "spectra/tonemap.h"

namespace nx {
namespace {

TEST(Tonemap, LogAverageLuminance) {
  const std::vector<Rgb> img{{1, 1, 1}, {4, 4, 4}};
  EXPECT_NEAR(logAverageLuminance(img), 2.0, 1e-5); // geometric mean of 1 and 4
}

// A uniform image maps to the key: L = 0.18, L_white = 0.18 (its largest value), so
// Ld = L (1 + L / Lw^2) / (1 + L) = (1 + 1/0.18) * 0.18 / 1.18.
TEST(Tonemap, UniformImageMapsThroughReinhardEquations) {
  const std::vector<Rgb> img(16, Rgb{3.0, 3.0, 3.0});
  const auto out = tonemapReinhard(img, {});
  const double l = 0.18, ld = l * (1 + l / (l * l)) / (1 + l);
  const int expected = static_cast<int>(std::lround(255 * srgbEncode(ld)));
  ASSERT_EQ(out.size(), 48u);
  for (uint8_t v : out) EXPECT_EQ(v, expected);
}

TEST(Tonemap, BrightestPixelIsWhiteAndOrderIsKept) {
  std::vector<Rgb> img;
  for (int i = 1; i <= 100; ++i) img.push_back({0.01 * i * i, 0.01 * i * i, 0.01 * i * i});
  const auto out = tonemapReinhard(img, {});
  EXPECT_EQ(out[3 * 99], 255);
  for (size_t i = 1; i < img.size(); ++i) EXPECT_GE(out[3 * i], out[3 * (i - 1)]);
}

TEST(Tonemap, ExplicitWhiteAndBadValues) {
  const std::vector<Rgb> img{{1, 1, 1}, {NAN, 0, 0}, {-1, -1, -1}, {INFINITY, 1, 1}};
  ReinhardSettings s;
  s.whiteLuminance = 1e9; // effectively L / (1 + L)
  const auto out = tonemapReinhard(img, s);
  EXPECT_EQ(out[3], 0); // NaN channel
  EXPECT_EQ(out[6], 0); // negative
  EXPECT_EQ(out[9], 0); // non-finite luminance: black
  // Log average over the finite pixels: exp((log(1+1e-6) + log(1e-6)) / 2).
  const double avg = std::exp(0.5 * (std::log(1 + 1e-6) + std::log(1e-6)));
  const double l = 0.18 / avg, ld = l / (1 + l);
  EXPECT_EQ(out[0], static_cast<int>(std::lround(255 * srgbEncode(std::min(ld, 1.0)))));
}

TEST(Tonemap, ColourRatiosSurviveBelowSaturation) {
  const std::vector<Rgb> img{{0.2, 0.1, 0.05}, {0.2, 0.1, 0.05}};
  ReinhardSettings s;
  s.whiteLuminance = 1e9;
  const auto out = tonemapReinhard(img, s);
  EXPECT_GT(out[0], out[1]);
  EXPECT_GT(out[1], out[2]);
  EXPECT_NEAR(srgbDecode(out[0] / 255.0) / srgbDecode(out[1] / 255.0), 2.0, 0.05);
}

} // namespace
} // namespace nx
