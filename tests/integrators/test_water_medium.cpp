// The built-in pure-water coefficients (Smith & Baker 1981, Table I) and their use in media
// with a unit scale.

#include <gtest/gtest.h>

#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "spectra/water.h"

namespace nx {
namespace {

double at(const Spectrum& s, double nm) {
  return std::get<TabulatedSpectrum>(s.kind())(nm) * s.scale();
}

// Values of the published table, between its rows (linear) and beyond its ends (held).
TEST(Water, PublishedTableValues) {
  const auto a = namedMediumCoefficient("water:absorption");
  const auto b = namedMediumCoefficient("water:scattering");
  ASSERT_TRUE(a && b);
  EXPECT_DOUBLE_EQ(at(*a, 440), 0.0145);
  EXPECT_DOUBLE_EQ(at(*a, 600), 0.244);
  EXPECT_NEAR(at(*a, 605), (0.244 + 0.289) / 2, 1e-12);
  EXPECT_DOUBLE_EQ(at(*a, 830), 2.07); // held beyond 800 nm
  EXPECT_DOUBLE_EQ(at(*b, 400), 0.0076);
  EXPECT_DOUBLE_EQ(at(*b, 500), 0.0029);
  EXPECT_FALSE(namedMediumCoefficient("water"));
  EXPECT_FALSE(namedMediumCoefficient("water:Absorption"));
}

// scale="0.01" turns the per-metre table into per-centimetre coefficients for a scene in cm.
TEST(Water, CoefficientScaleInAScene) {
  const RenderScene scene = resolveRenderScene(parseScene(
      "<scene><settings><xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode></"
      "settings><camera><position>0,0,-5</position>"
      "<look_at>0,0,0</look_at></camera><sphere><center>0,0,0</center><radius>1</radius>"
      "<material>thin_glass</material><medium><sigma_a scale=\"0.01\">water:absorption"
      "</sigma_a><sigma_s scale=\"0.01\">water:scattering</sigma_s></medium></sphere></scene>",
      "t.scn"));
  ASSERT_EQ(scene.media.size(), 1u);
  SampledWavelengths l;
  for (int i = 0; i < kLanes; ++i) l.lambda[i] = 600.0f + 10.0f * static_cast<float>(i);
  SampledSpectrum sa, ss, sfl;
  scene.media[0].coefficients(l, sa, ss, sfl);
  EXPECT_NEAR(sa[0], 0.00244, 1e-7);
  EXPECT_NEAR(ss[0], 0.000014, 1e-9);
  EXPECT_TRUE(scene.tables.empty()); // a built-in table that holds its ends warns of nothing
}

} // namespace
} // namespace nx
