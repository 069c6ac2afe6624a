#include <gtest/gtest.h>

#include "core/frame.h"
#include "core/math_util.h"
#include "integrators/lights/light_sampler.h"
#include "integrators/sampling.h"
#include "integrators/scene_reader.h"
#include "support/flat_wavelengths.h"
#include "support/light_pdf.h"
#include "support/statistics.h"

namespace nx {
namespace {

RenderScene sceneWithLight(const std::string& lights) {
  return buildRenderScene(
      parseScene("<scene><settings><xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode>"
                 "</settings><camera><position>0,0,-5</position><look_at>0,0,0</look_at>"
                 "</camera>" +
                     lights + "</scene>",
                 "t.scn"));
}

using test::pdfTowards;

// Directions towards a sphere light are uniform in the cone it subtends (chi-square in the
// cone's cos theta and phi), and pdf() agrees with sample().
TEST(LightSampler, SphereConeSamplingMatchesPdf) {
  const RenderScene s = sceneWithLight(
      "<sphere><center>0, 4, 0</center><radius>1.5</radius><material>matte</material>"
      "<emission>2</emission></sphere>");
  const LightSampler lights(s);
  const Vec3 p(0.3f, 0, 0.2f);
  const Vec3 axis = normalize(Vec3(0, 4, 0) - p);
  const double cosMax = std::sqrt(1 - 1.5 * 1.5 / dot(Vec3(0, 4, 0) - p, Vec3(0, 4, 0) - p));
  const Frame frame = Frame::fromNormal(axis);
  const int n = 100000, nz = 20, nphi = 20;
  std::vector<double> obs(nz * nphi, 0), exp(nz * nphi, n / double(nz * nphi));
  for (int i = 0; i < n; ++i) {
    LightSample ls;
    ASSERT_TRUE(lights.sample(p, 0.5f, samplePair(SamplerKind::Independent, i, 0, 0, 1),
                              test::flatWavelengths(500), ls));
    EXPECT_NEAR(ls.pdf, pdfTowards(s, lights, p, ls.wi), 1e-3f * ls.pdf);
    EXPECT_FLOAT_EQ(ls.radiance[0], 2.0f);
    const Vec3 local = frame.toLocal(ls.wi);
    const int iz = std::min(nz - 1, static_cast<int>((1 - local.z) / (1 - cosMax) * nz));
    const double phi = std::atan2(local.y, local.x) + kPi;
    obs[iz * nphi + std::min(nphi - 1, static_cast<int>(phi / (2 * kPi) * nphi))] += 1;
    // The sampled distance reaches the sphere's surface.
    const Vec3 q = p + ls.wi * ls.distance;
    EXPECT_NEAR(length(q - Vec3(0, 4, 0)), 1.5f, 1e-4f);
  }
  const auto [stat, dof] = test::chiSquare(obs, exp);
  EXPECT_LT(test::chiSquareZ(stat, dof), 4.0);
  EXPECT_EQ(pdfTowards(s, lights, p, -axis), 0.0f); // outside the cone
}

// Next-event estimation of the irradiance from a sphere of radiance L above a surface:
// E = pi L sin^2(theta_max) (the sphere entirely above the horizon).
TEST(LightSampler, IrradianceFromSphereLight) {
  const RenderScene s =
      sceneWithLight("<sphere><center>0, 3, 0</center><radius>1</radius><material>matte</material>"
                     "<emission>1</emission></sphere><light><position>0, 2, "
                     "0</position><color>0,0,0</color></light>");
  const LightSampler lights(s);
  ASSERT_EQ(lights.count(), 2);
  const Vec3 p(0, 0, 0), n(0, 1, 0);
  test::RunningStats stats;
  for (int i = 0; i < 200000; ++i) {
    LightSample ls;
    const float uChoice = sampleValue(SamplerKind::Independent, i, 0, 2, 1);
    if (!lights.sample(p, uChoice, samplePair(SamplerKind::Independent, i, 0, 0, 1),
                       test::flatWavelengths(500), ls)) {
      stats.add(0);
      continue;
    }
    stats.add(ls.radiance[0] * std::max(0.0f, dot(ls.wi, n)) / ls.pdf);
  }
  const double expected = kPi * (1.0 / 9.0);
  EXPECT_LT(std::abs(stats.mean - expected), 4 * stats.standardError());
  EXPECT_LT(stats.standardError(), 0.01 * expected);
}

TEST(LightSampler, PointLightInverseSquare) {
  const RenderScene s =
      sceneWithLight("<light><position>0, 2, 0</position><color>4, 4, 4</color></light>");
  const LightSampler lights(s);
  LightSample ls;
  ASSERT_TRUE(lights.sample(Vec3(0, 0, 0), 0.3f, {0.5f, 0.5f}, test::flatWavelengths(500), ls));
  EXPECT_TRUE(ls.delta);
  EXPECT_FLOAT_EQ(ls.distance, 2.0f);
  EXPECT_NEAR(ls.radiance[0], std::get<PointLight>(s.lights[0]).intensity(500) / 4, 1e-5);
}

TEST(LightSampler, InsideASphereLightEveryDirectionCounts) {
  const RenderScene s =
      sceneWithLight("<sphere><center>0,0,0</center><radius>10</radius><material>matte</material>"
                     "<emission>1</emission></sphere>");
  const LightSampler lights(s);
  for (int i = 0; i < 1000; ++i) {
    LightSample ls;
    ASSERT_TRUE(lights.sample(Vec3(1, 2, 3), 0.1f, samplePair(SamplerKind::Independent, i, 0, 0, 1),
                              test::flatWavelengths(500), ls));
    EXPECT_NEAR(ls.pdf, 1 / (4 * kPi), 1e-6);
    EXPECT_NEAR(length(Vec3(1, 2, 3) + ls.wi * ls.distance), 10.0f, 1e-4f);
  }
}

// A light of radius 6 seen from 1e12 away (a path that ran along a plane to its horizon): the
// cone of 1e-22 sr is sampled exactly, the estimate of the irradiance, pi L sin^2(theta max),
// holds per sample, and the MIS weight against a diffuse BSDF stays finite.
TEST(LightSampler, TinyConeFarAwayIsExactAndFinite) {
  const RenderScene s =
      sceneWithLight("<sphere><center>0,0,0</center><radius>6</radius><material>matte</material>"
                     "<emission>1</emission></sphere>");
  const LightSampler lights(s);
  const Vec3 p(1e12f, 0, 0), n(-1, 0, 0);
  const double d = 1e12, expected = kPi * 36.0 / (d * d);
  for (int i = 0; i < 100; ++i) {
    LightSample ls;
    ASSERT_TRUE(lights.sample(p, 0.5f, samplePair(SamplerKind::Independent, i, 0, 0, 1),
                              test::flatWavelengths(500), ls));
    ASSERT_TRUE(std::isfinite(ls.pdf));
    EXPECT_NEAR(ls.radiance[0] * dot(ls.wi, n) / ls.pdf, expected, 1e-5 * expected);
    EXPECT_NEAR(ls.distance, static_cast<float>(d - 6), 1e-6f * static_cast<float>(d));
    EXPECT_EQ(powerHeuristic(ls.pdf, cosineHemispherePdf(dot(ls.wi, n))), 1.0f);
  }
}

} // namespace
} // namespace nx
