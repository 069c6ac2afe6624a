// Spectral channel names of the Fichet et al. 2021 layout.

#include <gtest/gtest.h>

#include "io/fichet_channels.h"

namespace nx {
namespace {

TEST(FichetChannels, UnitsPrefixesAndOrder) {
  std::string kind;
  // 550 nm as hertz: c / 550e-9 = 545.0771963636... THz
  const auto c = fichetSpectralChannels({"R", "S0.600nm", "S0.0,5um", "S0.545,0771963636THz",
                                         "S0.5,2e2nm", "S0.4dam", "S1.500nm", "Variance.S0.600nm",
                                         "S0.nm", "S0.abcnm", "S4.500nm"},
                                        kind);
  EXPECT_EQ(kind, "S0");
  ASSERT_EQ(c.size(), 5u); // 4 dam (decametres) = 4e10 nm is a channel too, sorted last
  EXPECT_NEAR(c[0].nm, 500, 1e-9);
  EXPECT_EQ(c[0].name, "S0.0,5um");
  EXPECT_NEAR(c[1].nm, 520, 1e-9);
  EXPECT_NEAR(c[2].nm, 550, 1e-6);
  EXPECT_NEAR(c[3].nm, 600, 1e-9);
  EXPECT_NEAR(c[4].nm, 4e10, 1);
}

TEST(FichetChannels, ReflectiveOnlyWhenNoEmissive) {
  std::string kind;
  auto c = fichetSpectralChannels({"T.500nm", "T.400nm"}, kind);
  EXPECT_EQ(kind, "T");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].name, "T.400nm");
  c = fichetSpectralChannels({"T.500nm", "S0.450nm"}, kind);
  EXPECT_EQ(kind, "S0");
  ASSERT_EQ(c.size(), 1u);
  c = fichetSpectralChannels({"R", "G", "B", "S2.500nm"}, kind);
  EXPECT_EQ(kind, "");
  EXPECT_TRUE(c.empty());
}

} // namespace
} // namespace nx
