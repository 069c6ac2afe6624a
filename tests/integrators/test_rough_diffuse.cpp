// Rough diffuse (Fujii's Oren-Nayar with EON's multiple scattering): its single-scattering
// albedo against independent quadratures of the formula and its closed form at normal
// incidence, exact energy conservation for a white surface, the Lambertian limit, the
// retro-reflection that sets it apart, EON's coloured multiple scattering, a furnace render per
// band, a fluorescent base, and its scene errors. (Sampling, reciprocity, albedo at most 1 and
// derivatives: MaterialConformance, over the registry's cases.)

#include <gtest/gtest.h>

#include <cmath>

#include "integrators/materials/bsdf.h"
#include "integrators/materials/kinds/rough_diffuse.h"
#include "integrators/renderer.h"
#include "spectra/bands.h"
#include "support/direction_chi_square.h"
#include "support/errors.h"
#include "support/material_checks.h"
#include "support/render_checks.h"

namespace nx {
namespace {

Material roughMatte(double sigma) {
  return resolveRenderScene(
             parseScene(sceneText("<xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode>",
                                  "<position>0,0,-5</position><look_at>0,0,0</look_at>",
                                  "<sphere><center>0,0,0</center><radius>1</radius><material>"
                                  "rough_matte</material><sigma>" +
                                      std::to_string(sigma) +
                                      "</sigma><reflectance>1</reflectance></sphere>"),
                        "t.scn"))
      .materials[0];
}

Vec3 fromAngles(double cosTheta, double phi) {
  const double s = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
  return {static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
          static_cast<float>(cosTheta)};
}

// integral of f |cos| over the hemisphere by the midpoint rule in cos(theta) and phi (a grid
// unlike the build's, which integrates over theta).
double albedoByQuadrature(const SurfaceBsdf& bsdf, int lane) {
  const int nc = 300, np = 300;
  double sum = 0;
  for (int i = 0; i < nc; ++i)
    for (int j = 0; j < np; ++j) {
      const Vec3 wi = fromAngles((i + 0.5) / nc, (j + 0.5) / np * 2 * kPi);
      sum += bsdf.f(wi)[lane];
    }
  return sum * (1.0 / nc) * (2 * kPi / np);
}

// At normal incidence s = 0 everywhere, so the single-scattering albedo is Fujii's A exactly;
// elsewhere the table matches the formula integrated on another grid.
TEST(RoughDiffuse, SingleScatteringAlbedoMatchesItsFormula) {
  for (double sigma : {0.0, 0.2, 0.5, 1.0}) {
    const Material m = roughMatte(sigma);
    const double a = 1 / (1 + (kPi / 2 - 2.0 / 3.0) * sigma), b = sigma * a;
    EXPECT_NEAR(roughDiffuseLobeOf(m).a, a, 1e-6);
    EXPECT_NEAR(roughDiffuseAlbedo(roughDiffuseLobeOf(m), 1.0f), a, 2e-4) << sigma;
    for (double mu : {0.9, 0.5, 0.13, 0.02}) {
      const double so = std::sqrt(1 - mu * mu);
      double e = 0;
      const int nc = 600, np = 600;
      for (int i = 0; i < nc; ++i)
        for (int j = 0; j < np; ++j) {
          const double ci = (i + 0.5) / nc, si = std::sqrt(1 - ci * ci);
          const double s = si * so * std::cos((j + 0.5) / np * 2 * kPi);
          e += (a + b * (s > 0 ? s / std::max(ci, mu) : s)) * ci;
        }
      e *= (1.0 / nc) * (2 * kPi / np) / kPi;
      EXPECT_NEAR(roughDiffuseAlbedo(roughDiffuseLobeOf(m), static_cast<float>(mu)), e, 5e-4)
          << "sigma " << sigma << " mu " << mu;
    }
  }
}

// A white rough surface reflects everything from every direction (EON's multiple scattering
// puts back what single scattering loses: 1 - E(mu_o) in all); rougher surfaces lose more to
// single scattering alone (0.55 at sigma 1).
TEST(RoughDiffuse, WhiteSurfaceKeepsAllEnergy) {
  const SampledWavelengths l = test::laneWavelengths();
  for (double sigma : {0.1, 0.5, 1.0}) {
    const Material m = roughMatte(sigma);
    for (double mu : {1.0, 0.6, 0.2, 0.05}) {
      const SurfaceBsdf bsdf(m, l, SampledSpectrum::filled(1.0f), Vec3(0, 0, 1),
                             fromAngles(mu, 0.3));
      EXPECT_NEAR(albedoByQuadrature(bsdf, 0), 1.0, 3e-3) << "sigma " << sigma << " mu " << mu;
      test::RunningStats s;
      for (uint32_t i = 0; i < 50000; ++i) {
        BsdfSample b;
        s.add(bsdf.sample(0.5f, uniform2(i), b) ? b.weight[0] : 0.0);
      }
      EXPECT_NEAR(s.mean, 1.0, 5 * s.standardError() + 3e-3) << "sigma " << sigma << " mu " << mu;
    }
  }
  EXPECT_LT(roughDiffuseAlbedo(roughDiffuseLobeOf(roughMatte(1.0)), 1.0f), 0.56f);
}

// sigma = 0 is Lambertian: f = rho |cos| / pi, exactly.
TEST(RoughDiffuse, SmoothLimitIsLambertian) {
  const SampledWavelengths l = test::laneWavelengths();
  const Material m = roughMatte(0.0);
  for (uint32_t i = 0; i < 200; ++i) {
    const Vec3 wo = fromAngles(0.05 + 0.95 * uniform2(i).u, 6.28 * uniform2(i).v);
    const Vec3 wi = fromAngles(0.05 + 0.95 * uniform2(i + 500).u, 6.28 * uniform2(i + 500).v);
    const SurfaceBsdf bsdf(m, l, SampledSpectrum::filled(0.6f), Vec3(0, 0, 1), wo);
    EXPECT_NEAR(bsdf.f(wi)[0], 0.6 * wi.z / kPi, 1e-6);
  }
}

// What sets a rough surface apart (Oren and Nayar 1994): lit and seen from the same grazing
// direction it is brighter than a Lambertian surface of the same albedo, and seen opposite the
// light darker.
TEST(RoughDiffuse, RetroReflectsAtGrazingAngles) {
  const SampledWavelengths l = test::laneWavelengths();
  const Material m = roughMatte(0.8);
  const Vec3 light = fromAngles(0.2, 0.0), back = fromAngles(0.2, 0.0),
             opposite = fromAngles(0.2, kPi);
  const SurfaceBsdf seenBack(m, l, SampledSpectrum::filled(1.0f), Vec3(0, 0, 1), back);
  const SurfaceBsdf seenOpposite(m, l, SampledSpectrum::filled(1.0f), Vec3(0, 0, 1), opposite);
  const double lambert = light.z / kPi;
  EXPECT_GT(seenBack.f(light)[0], 1.5 * lambert);
  EXPECT_LT(seenOpposite.f(light)[0], 0.8 * lambert);
}

// EON's multiple scattering is coloured: rho_ms = rho^2 E / (1 - rho (1 - E)) < rho below 1, so
// a grey rough surface reflects less than rho; its reflectance slope is the model's own
// (d ln f / d rho against a difference in rho).
TEST(RoughDiffuse, MultipleScatteringAndReflectanceSlope) {
  const SampledWavelengths l = test::laneWavelengths();
  const Material m = roughMatte(1.0);
  const double e = roughDiffuseLobeOf(m).meanAlbedo;
  for (double rho : {0.2, 0.5, 0.9})
    EXPECT_NEAR(roughDiffuseMultipleAlbedo(roughDiffuseLobeOf(m), static_cast<float>(rho)),
                rho * rho * e / (1 - rho * (1 - e)), 1e-6);
  const Vec3 wo = fromAngles(0.4, 0.2), wi = fromAngles(0.7, 2.0);
  for (float rho : {0.2f, 0.5f, 0.9f}) {
    const SurfaceBsdf bsdf(m, l, SampledSpectrum::filled(rho), Vec3(0, 0, 1), wo);
    EXPECT_LT(albedoByQuadrature(bsdf, 0), rho);
    const float h = 1e-3f;
    const SurfaceBsdf up(m, l, SampledSpectrum::filled(rho + h), Vec3(0, 0, 1), wo),
        down(m, l, SampledSpectrum::filled(rho - h), Vec3(0, 0, 1), wo);
    const double slope = (std::log(up.f(wi)[0]) - std::log(down.f(wi)[0])) / (2 * h);
    bool zero = false;
    EXPECT_NEAR(bsdf.reflectanceLogSlope(wi, rho, false, true, zero), slope, 1e-3 * slope);
    EXPECT_FALSE(zero);
  }
}

const std::string kFurnace =
    "<xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>4</depth><sampl>2048</sampl>"
    "<background>1</background>";
const std::string kAxis = "<position>0,0,-100</position><look_at>0,0,0</look_at><fov>0.02</fov>";

// Under a uniform background, along the sphere's axis (normal incidence), every band reads the
// albedo for the band's reflectance by quadrature of the BSDF; a white surface reads 1.
TEST(RoughDiffuse, FurnaceRenderPerBand) {
  const RenderOutput white = renderText(
      sceneText(kFurnace, kAxis,
                "<sphere><center>0,0,0</center><radius>1</radius><material>rough_matte</material>"
                "<sigma>0.7</sigma><reflectance>1</reflectance></sphere>"));
  expectBands(
      white.film, [](int) { return 1.0; }, 0.01, {}, "white rough matte");
  const RenderOutput grey = renderText(
      sceneText(kFurnace, kAxis,
                "<sphere><center>0,0,0</center><radius>1</radius><material>rough_matte</material>"
                "<sigma>0.7</sigma><reflectance>0.5</reflectance></sphere>"));
  const SampledWavelengths l = test::laneWavelengths();
  const Material m = roughMatte(0.7); // the BSDF keeps a reference: it must outlive it
  const SurfaceBsdf bsdf(m, l, SampledSpectrum::filled(0.5f), Vec3(0, 0, 1), Vec3(0, 0, 1));
  const double expected = albedoByQuadrature(bsdf, 0);
  EXPECT_LT(expected, 0.49);
  expectBands(
      grey.film, [&](int) { return expected; }, 0.01, {}, "grey rough matte");
}

// A fluorescent base: with sigma = 0 it renders what the fluorescent matte renders, band by
// band; a rough one still fluoresces in its emission band.
TEST(RoughDiffuse, FluorescentBase) {
  const auto scene = test::fluorescentSphereScene;
  const RenderOutput matte = renderText(scene("<material>matte</material>"));
  const RenderOutput smooth = renderText(scene("<material>rough_matte</material><sigma>0</sigma>"));
  const RenderOutput rough = renderText(scene("<material>rough_matte</material><sigma>1</sigma>"));
  int emission = 0; // the band nearest the emission peak, 540 nm
  for (int b = 0; b < matte.film.bands().count(); ++b) {
    const test::RunningStats x = bandStats(matte.film, b), y = bandStats(smooth.film, b);
    EXPECT_LT(std::abs(x.mean - y.mean),
              5 * std::hypot(x.standardError(), y.standardError()) + 1e-6)
        << "band " << matte.film.bands().centroid(b);
    if (std::abs(matte.film.bands().centroid(b) - 540) <
        std::abs(matte.film.bands().centroid(emission) - 540))
      emission = b;
  }
  EXPECT_GT(bandStats(rough.film, emission).mean, 0.5 * bandStats(matte.film, emission).mean);
}

TEST(RoughDiffuse, SceneErrors) {
  const auto error = test::sphereSceneError;
  EXPECT_NE(error("<material>rough_matte</material><reflectance>0.5</reflectance><sigma>1.5"
                  "</sigma>")
                .find("sigma"),
            std::string::npos);
  EXPECT_NE(error("<material>rough_matte</material><reflectance>0.5</reflectance><roughness>0.3"
                  "</roughness>")
                .find("on rough_matte, found <roughness>"),
            std::string::npos);
  EXPECT_NE(error("<material>rough_matte</material>").find("expected <reflectance> or <color>"),
            std::string::npos);
}

} // namespace
} // namespace nx
