// Rough dielectrics (Walter et al. 2007): chi-square of reflection and refraction sampling over
// the whole sphere, energy against a near-smooth limit, generalised reciprocity, and dispersion
// through a frosted surface against renders at each band's own index.

#include <gtest/gtest.h>

#include <cmath>

#include "integrators/materials/bsdf.h"
#include "integrators/renderer.h"
#include "spectra/bands.h"
#include "support/direction_chi_square.h"
#include "support/errors.h"
#include "support/material_checks.h"
#include "support/render_checks.h"

namespace nx {
namespace {

Material roughGlass(float ax, float ay, double ior) {
  Material m;
  m.kind = MaterialKind::Dielectric;
  m.reflectance = Spectrum(ConstantSpectrum{1.0});
  m.ior = IorModel::constant(ior);
  m.alphaU = ax;
  m.alphaV = ay;
  return m;
}

// Reflected and refracted directions together follow pdf(wi), from outside and from inside
// (where total internal reflection takes part), isotropic and anisotropic.
TEST(RoughDielectric, SamplingFollowsItsPdf) {
  const SampledWavelengths l = test::laneWavelengths();
  const Vec3 ng(0, 0, 1);
  for (const auto& [ax, ay] : {std::pair{0.3f, 0.3f}, std::pair{0.6f, 0.6f}, std::pair{0.2f, 0.5f}})
    for (const Vec3& wo :
         {normalize(Vec3(0.3f, -0.2f, 0.9f)), normalize(Vec3(-0.8f, 0.1f, 0.3f)),
          normalize(Vec3(0.2f, 0.3f, -0.8f)), normalize(Vec3(0.7f, 0.0f, -0.5f))}) {
      const Material m = roughGlass(ax, ay, 1.5);
      SurfaceBsdf bsdf(m, l, SampledSpectrum::filled(1.0f), ng, wo);
      bsdf.orient(Vec3(1, 0.5f, 0));
      uint32_t k = 0;
      expectDirectionsFollowPdf(
          [&](Sample2 u) {
            BsdfSample s;
            const float uLobe = uniform2(1000000 + k++).u;
            return bsdf.sample(uLobe, u, s) ? s.wi : Vec3(0, 0, 0);
          },
          [&](const Vec3& wi) { return bsdf.pdf(wi); });
    }
}

// The sampler's mean weight (energy transport) equals the integral of f |cos| by quadrature
// (the weights are f |cos| / pdf), is at most 1, and tends to 1 (a smooth interface loses
// nothing) as the roughness vanishes.
TEST(RoughDielectric, EnergyAgainstQuadratureAndTheSmoothLimit) {
  const SampledWavelengths l = test::laneWavelengths();
  for (float a : {0.02f, 0.3f, 0.8f})
    for (float side : {1.0f, -1.0f}) {
      const Vec3 wo = normalize(Vec3(0.5f, 0.2f, 0.7f * side));
      const Material m = roughGlass(a, a, 1.5);
      const SurfaceBsdf bsdf(m, l, SampledSpectrum::filled(1.0f), Vec3(0, 0, 1), wo,
                             TransportMode::Energy);
      test::RunningStats s;
      for (uint32_t i = 0; i < 200000; ++i) {
        BsdfSample b;
        s.add(bsdf.sample(uniform2(500000 + i).u, uniform2(i), b) ? b.weight[0] : 0.0);
      }
      EXPECT_LE(s.mean, 1.0 + 3 * s.standardError());
      if (a < 0.05f) {
        EXPECT_NEAR(s.mean, 1.0, 0.01) << "near-smooth, side " << side;
        continue;
      }
      double e = 0;
      const int nt = 1200, np = 480;
      for (int i = 0; i < nt; ++i)
        for (int j = 0; j < np; ++j) {
          const double th = (i + 0.5) / nt * kPi, ph = (j + 0.5) / np * 2 * kPi;
          const Vec3 wi(static_cast<float>(std::sin(th) * std::cos(ph)),
                        static_cast<float>(std::sin(th) * std::sin(ph)),
                        static_cast<float>(std::cos(th)));
          e += bsdf.f(wi)[0] * std::sin(th) * (kPi / nt) * (2 * kPi / np);
        }
      EXPECT_NEAR(s.mean, e, 5 * s.standardError() + 3e-3) << "alpha " << a << " side " << side;
      std::printf("rough glass n 1.5, alpha %.2f, %s: R + T = %.4f (quadrature %.4f)\n", a,
                  side > 0 ? "outside" : "inside", s.mean, e);
    }
}

// Energy-transport BSDFs obey f(wo, wi) / n(wi's side)^2 = f(wi, wo) / n(wo's side)^2 (Veach
// 1997, eq. 5.14); reflection is symmetric.
TEST(RoughDielectric, GeneralisedReciprocity) {
  const SampledWavelengths l = test::laneWavelengths();
  const Material m = roughGlass(0.25f, 0.4f, 1.5);
  const Vec3 ng(0, 0, 1);
  int checked = 0;
  for (uint32_t k = 0; k < 400; ++k) {
    auto dir = [](Sample2 u) {
      const float z = -0.95f + 1.9f * u.u, r = std::sqrt(1 - z * z);
      const float p = 2 * static_cast<float>(kPi) * u.v;
      return Vec3(r * std::cos(p), r * std::sin(p), z);
    };
    const Vec3 a = dir(uniform2(2 * k)), b = dir(uniform2(2 * k + 1));
    SurfaceBsdf fa(m, l, SampledSpectrum::filled(1.0f), ng, a, TransportMode::Energy);
    SurfaceBsdf fb(m, l, SampledSpectrum::filled(1.0f), ng, b, TransportMode::Energy);
    fa.orient(Vec3(1, 0, 0));
    fb.orient(Vec3(1, 0, 0));
    const double nA = a.z > 0 ? 1.0 : 1.5, nB = b.z > 0 ? 1.0 : 1.5;
    const double x = fa.f(b)[0] / std::abs(b.z) / (nB * nB);
    const double y = fb.f(a)[0] / std::abs(a.z) / (nA * nA);
    EXPECT_NEAR(x, y, 2e-4 * std::max(1.0, std::abs(x))) << "pair " << k;
    checked += x > 0;
  }
  EXPECT_GT(checked, 100);
}

// Dispersion through a frosted surface: a rough plane of glass with Cauchy index 1.5 + 0.03 /
// l^2 (l in um) over a sphere light, seen from above. Each band of the dispersive render
// equals the same band rendered with the constant index of that band's centre (the index
// changes by under 0.002 within a 10 nm band).
TEST(RoughDielectric, DispersionMatchesPerBandIndices) {
  auto scene = [](const std::string& ior) {
    return sceneText("<xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>3</depth>"
                     "<sampl>2048</sampl>",
                     "<position>0,2,-1.5</position><look_at>0,0,0</look_at><fov>20</fov>",
                     "<plane><normal>0,1,0</normal><distance>0</distance><material>glass"
                     "</material><alpha>0.3</alpha><ior>" +
                         ior +
                         "</ior></plane><sphere><center>0,-3,0.5</center><radius>2</radius>"
                         "<material>matte</material><reflectance>0</reflectance><emission>"
                         "1</emission></sphere>");
  };
  const RenderOutput dispersive = renderText(scene("cauchy: 1.5, 0.03"));
  const Film& film = dispersive.film;
  for (int b : {4, 16, 28}) { // bands near 440, 560, 680 nm
    const double um = film.bands().centroid(b) / 1000;
    const RenderOutput fixed = renderText(scene(std::to_string(1.5 + 0.03 / (um * um))));
    const test::RunningStats d = bandStats(film, b), f = bandStats(fixed.film, b);
    EXPECT_LT(std::abs(d.mean - f.mean),
              5 * std::hypot(d.standardError(), f.standardError()) + 1e-3 * f.mean)
        << "band " << film.bands().centroid(b) << ": dispersive " << d.mean << " fixed " << f.mean;
    EXPECT_LT(d.standardError(), 0.05 * d.mean);
    EXPECT_GT(f.mean, 0.05);
  }
}

TEST(RoughDielectric, SceneErrors) {
  const auto error = test::sphereSceneError;
  EXPECT_NE(error("<material>thin_glass</material><alpha>0.2</alpha>")
                .find("on thin_glass, found <alpha> (a thin wall stays smooth)"),
            std::string::npos);
  EXPECT_NE(error("<material>glass</material><alpha>0.2</alpha><coating><thickness>100"
                  "</thickness><ior>1.4</ior></coating>")
                .find("found it on a rough one"),
            std::string::npos);
  EXPECT_NE(error("<material>matte</material><reflectance>0.5</reflectance><alpha>0.1</alpha>")
                .find("on matte, found <alpha> (GGX roughness is for conductors and dielectrics"),
            std::string::npos);
}

} // namespace
} // namespace nx
