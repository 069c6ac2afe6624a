// Coated diffuse (a Lambertian base under a clear coat): its albedo against the closed form of
// the summed internal reflections, exact energy conservation for a white base, chi-square of its
// diffuse sampling, reciprocity, a render per band, and a fluorescent base under a coat.

#include <gtest/gtest.h>

#include <cmath>

#include "integrators/materials/bsdf.h"
#include "integrators/materials/fresnel.h"
#include "integrators/renderer.h"
#include "spectra/bands.h"
#include "support/direction_chi_square.h"
#include "support/errors.h"
#include "support/material_checks.h"
#include "support/render_checks.h"

namespace nx {
namespace {

// Fi = 1 - (1 - Fe) / n^2, Fe = 2 integral F(mu) mu dmu, by an independent quadrature (Simpson).
double internalReflectance(double n) {
  const int steps = 2000;
  double fe = 0;
  for (int i = 0; i <= steps; ++i) {
    const double mu = static_cast<double>(i) / steps;
    const double w = (i == 0 || i == steps) ? 1 : (i % 2 ? 4 : 2);
    fe += w * 2 * fresnelDielectric(static_cast<float>(mu), static_cast<float>(n)) * mu;
  }
  fe /= 3.0 * steps;
  return 1 - (1 - fe) / (n * n);
}

// Directional albedo: F(o) + (1 - F(o)) rho (1 - Fi) / (1 - rho Fi).
double albedo(double cosO, double n, double rho) {
  const double f = fresnelDielectric(static_cast<float>(cosO), static_cast<float>(n));
  const double fi = internalReflectance(n);
  return f + (1 - f) * rho * (1 - fi) / (1 - rho * fi);
}

Material coated(double n) {
  Material m;
  m.kind = MaterialKind::CoatedDiffuse;
  m.reflectance = Spectrum(ConstantSpectrum{1.0});
  m.ior = IorModel::constant(n);
  m.coatInternalReflectance = static_cast<float>(internalReflectance(n));
  return m;
}

// The mean sample weight is the albedo of the closed form (1 for a white base: the coat and the
// internal reflections lose nothing), and quadrature of f |cos| gives its diffuse part.
TEST(CoatedDiffuse, AlbedoMatchesTheClosedForm) {
  const SampledWavelengths l = test::laneWavelengths();
  for (double n : {1.33, 1.5, 2.0})
    for (double rho : {1.0, 0.5, 0.1})
      for (double cosO : {1.0, 0.5, 0.1}) {
        const Material m = coated(n);
        const Vec3 wo(static_cast<float>(std::sqrt(1 - cosO * cosO)), 0, static_cast<float>(cosO));
        const SurfaceBsdf bsdf(m, l, SampledSpectrum::filled(static_cast<float>(rho)),
                               Vec3(0, 0, 1), wo);
        test::RunningStats s;
        for (uint32_t i = 0; i < 100000; ++i) {
          BsdfSample b;
          s.add(bsdf.sample(uniform2(300000 + i).u, uniform2(i), b) ? b.weight[0] : 0.0);
        }
        const double expected = albedo(cosO, n, rho);
        EXPECT_NEAR(s.mean, expected, 5 * s.standardError() + 1e-4)
            << "n " << n << " rho " << rho << " cos " << cosO;
        if (rho == 1.0) {
          EXPECT_NEAR(s.mean, 1.0, 5 * s.standardError() + 1e-4);
        }
        double diffuse = 0;
        const int nt = 400, np = 200;
        for (int i = 0; i < nt; ++i)
          for (int j = 0; j < np; ++j) {
            const double th = (i + 0.5) / nt * kPi / 2, ph = (j + 0.5) / np * 2 * kPi;
            const Vec3 wi(static_cast<float>(std::sin(th) * std::cos(ph)),
                          static_cast<float>(std::sin(th) * std::sin(ph)),
                          static_cast<float>(std::cos(th)));
            diffuse += bsdf.f(wi)[0] * std::sin(th) * (kPi / 2 / nt) * (2 * kPi / np);
          }
        EXPECT_NEAR(diffuse + fresnelDielectric(static_cast<float>(cosO), static_cast<float>(n)),
                    expected, 2e-4);
      }
}

TEST(CoatedDiffuse, DiffuseSamplingFollowsItsPdf) {
  const SampledWavelengths l = test::laneWavelengths();
  const Material m = coated(1.5);
  for (const Vec3& wo : {normalize(Vec3(0.2f, 0.1f, 0.9f)), normalize(Vec3(-0.9f, 0.2f, 0.2f))}) {
    const SurfaceBsdf bsdf(m, l, SampledSpectrum::filled(0.6f), Vec3(0, 0, 1), wo);
    uint32_t k = 0;
    expectDirectionsFollowPdf(
        [&](Sample2 u) {
          BsdfSample s;
          return bsdf.sample(uniform2(900000 + k++).u, u, s) && !s.specular ? s.wi : Vec3(0, 0, 0);
        },
        [&](const Vec3& wi) { return bsdf.pdf(wi); });
  }
}

TEST(CoatedDiffuse, Reciprocity) {
  const SampledWavelengths l = test::laneWavelengths();
  const Material m = coated(1.5);
  for (uint32_t i = 0; i < 100; ++i) {
    auto dir = [](Sample2 u) {
      const float z = 0.05f + 0.95f * u.u, r = std::sqrt(1 - z * z);
      const float p = 2 * static_cast<float>(kPi) * u.v;
      return Vec3(r * std::cos(p), r * std::sin(p), z);
    };
    const Vec3 a = dir(uniform2(2 * i)), b = dir(uniform2(2 * i + 1));
    const SurfaceBsdf fa(m, l, SampledSpectrum::filled(0.7f), Vec3(0, 0, 1), a);
    const SurfaceBsdf fb(m, l, SampledSpectrum::filled(0.7f), Vec3(0, 0, 1), b);
    EXPECT_NEAR(fa.f(b)[0] / b.z, fb.f(a)[0] / a.z, 1e-6f);
  }
}

const std::string kFurnace =
    "<xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>4</depth><sampl>4096</sampl>"
    "<background>1</background>";
const std::string kAxis = "<position>0,0,-100</position><look_at>0,0,0</look_at><fov>0.02</fov>";

// Rendered under a uniform background, along the sphere's axis: every band reads the closed
// form for the band's base reflectance (rising from 0.1 to 0.9); a white base reads 1.
TEST(CoatedDiffuse, RenderedAlbedoPerBand) {
  const RenderOutput out = renderText(sceneText(
      kFurnace, kAxis,
      "<sphere><center>0,0,0</center><radius>1</radius><material>coated</material>"
      "<ior>1.5</ior><reflectance extrapolate=\"hold\">400:0.1, 700:0.9</reflectance></sphere>"));
  std::vector<double> nm, v;
  for (double x = 350; x <= 850; x += 0.25) {
    nm.push_back(x);
    v.push_back(albedo(1.0, 1.5, 0.1 + 0.8 * (std::clamp(x, 400.0, 700.0) - 400) / 300));
  }
  const Spectrum a(TabulatedSpectrum{nm, v});
  expectBands(
      out.film, [&](int b) { return bandAverage(a, out.film.bands(), b); }, 0.01, {}, "coated");
  const RenderOutput white = renderText(
      sceneText(kFurnace, kAxis,
                "<sphere><center>0,0,0</center><radius>1</radius><material>coated</material>"
                "<reflectance>1</reflectance></sphere>"));
  expectBands(
      white.film, [](int) { return 1.0; }, 0.01, {}, "white coated");
}

// A fluorescent base keeps working under a coat: with a coat of index 1.0001 (no reflection
// either way) the coated surface renders what the bare fluorescent matte renders, band by band
// (elastic and fluorescent light alike); a real coat (n 1.5) dims the emission band.
TEST(CoatedDiffuse, FluorescentBaseUnderACoat) {
  const auto scene = test::fluorescentSphereScene;
  const RenderOutput bare = renderText(scene("<material>matte</material>"));
  const RenderOutput clear = renderText(scene("<material>coated</material><ior>1.0001</ior>"));
  const RenderOutput coat = renderText(scene("<material>coated</material><ior>1.5</ior>"));
  for (int b = 0; b < bare.film.bands().count(); ++b) {
    const test::RunningStats x = bandStats(bare.film, b), y = bandStats(clear.film, b);
    EXPECT_LT(std::abs(x.mean - y.mean),
              5 * std::hypot(x.standardError(), y.standardError()) + 1e-6)
        << "band " << bare.film.bands().centroid(b);
  }
  int emission = 0; // the band nearest the emission peak, 540 nm
  for (int b = 0; b < bare.film.bands().count(); ++b)
    if (std::abs(bare.film.bands().centroid(b) - 540) <
        std::abs(bare.film.bands().centroid(emission) - 540))
      emission = b;
  const double bareEmission = bandStats(bare.film, emission).mean;
  EXPECT_GT(bareEmission, 0.05);
  EXPECT_LT(bandStats(coat.film, emission).mean, bareEmission);
}

TEST(CoatedDiffuse, SceneErrors) {
  const auto error = test::sphereSceneError;
  EXPECT_NE(error("<material>coated</material><reflectance>0.5</reflectance><ior>bk7</ior>")
                .find("expected a constant <ior> for a coat"),
            std::string::npos);
  EXPECT_NE(error("<material>coated</material><reflectance>0.5</reflectance><roughness>0.3"
                  "</roughness>")
                .find("on coated, found <roughness> (a Lambertian base under a smooth coat)"),
            std::string::npos);
  EXPECT_NE(error("<material>coated</material>").find("expected <reflectance> or <color>"),
            std::string::npos);
}

} // namespace
} // namespace nx
