#include <gtest/gtest.h>

#include "core/error.h"
#include "spectra/sensor.h"

namespace nx {
namespace {

TEST(Bands, DefaultIs31BandsOf10nm) {
  const SpectralBands b = SpectralBands::defaults();
  EXPECT_EQ(b.count(), 31);
  EXPECT_DOUBLE_EQ(b.centre(0), 400);
  EXPECT_DOUBLE_EQ(b.centre(30), 700);
  EXPECT_DOUBLE_EQ(b.lower(0), 395);
  EXPECT_DOUBLE_EQ(b.upper(30), 705);
  EXPECT_EQ(b.bandOf(394.9), -1);
  EXPECT_EQ(b.bandOf(395), 0);
  EXPECT_EQ(b.bandOf(404.99), 0);
  EXPECT_EQ(b.bandOf(405), 1);
  EXPECT_EQ(b.bandOf(704.9), 30);
  EXPECT_EQ(b.bandOf(705), -1);
}

TEST(Bands, Parse) {
  const SpectralBands b = SpectralBands::parse("420:720:5");
  EXPECT_EQ(b.count(), 61);
  EXPECT_EQ(b.toString(), "420:720:5");
  EXPECT_EQ(SpectralBands::parse("550:550:1").count(), 1);
  for (const char* bad : {"400:700", "400:700:0", "700:400:10", "400:705:10", "a:700:10",
                          "400:700:10:1", "200:700:10", "400:2000:10", "400:700:-10"})
    EXPECT_THROW(SpectralBands::parse(bad), Error) << bad;
  try {
    SpectralBands::parse("400:705:10");
  } catch (const Error& e) {
    EXPECT_STREQ(
        e.what(),
        "bands '400:705:10': expected END - START to be a multiple of STEP, found 400:705:10");
  }
}

// The text form reads back as exactly the same bands (it is stored in the EXR, and the
// channels are found by the centres it gives): 6 significant digits lost 400.00001.
TEST(Bands, TextRoundTripsExactly) {
  for (const char* text :
       {"400.00001:700.00001:10", "400:700:10", "412.3456789:412.3456789:0.5", "300.1:699.9:0.2"}) {
    const SpectralBands b = SpectralBands::parse(text);
    const SpectralBands back = SpectralBands::parse(b.toString());
    EXPECT_EQ(back.startNm, b.startNm) << text;
    EXPECT_EQ(back.endNm, b.endNm) << text;
    EXPECT_EQ(back.stepNm, b.stepNm) << text;
  }
  EXPECT_EQ(SpectralBands::parse("400.00001:700.00001:10").toString(), "400.00001:700.00001:10");
  // Steps below 0.001 nm would give bands the same channel name (6 decimals).
  EXPECT_THROW(SpectralBands::parse("400:400.0004:0.0001"), Error);
}

TEST(Bands, AverageOfLinearSpectrumIsItsCentreValue) {
  const SpectralBands b = SpectralBands::defaults();
  const Spectrum s(makeTabulated({300, 900}, {0, 6}, "t")); // 0.01 per nm
  for (int i = 0; i < b.count(); ++i)
    EXPECT_NEAR(bandAverage(s, Sensor(b), i), s(b.centre(i)), 1e-9);
}

} // namespace
} // namespace nx
