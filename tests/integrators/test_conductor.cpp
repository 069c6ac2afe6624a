// Conductors: the Fresnel reflectance of complex indices against closed forms, the GGX
// distribution's normalisations, chi-square of visible-normal sampling, the white furnace
// against an independent quadrature, reciprocity, anisotropy, measured metals, a render.

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "integrators/materials/bsdf.h"
#include "integrators/materials/fresnel.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "spectra/bands.h"
#include "spectra/metals.h"
#include "support/direction_chi_square.h"
#include "support/errors.h"
#include "support/material_checks.h"
#include "support/render_checks.h"

namespace nx {
namespace {

// The conductor Fresnel reflectance from the complex amplitudes (Born & Wolf 14.2) in double:
// r_s = (cos_i - n cos_t) / (cos_i + n cos_t), r_p = (n cos_i - cos_t) / (n cos_i + cos_t),
// cos_t = sqrt(1 - sin_i^2 / n^2): independent of the real-arithmetic form under test.
double fresnelReference(double c, double n, double k) {
  using C = std::complex<double>;
  const C eta(n, k);
  const C cosT = std::sqrt(C(1.0) - (1 - c * c) / (eta * eta));
  const C rs = (c - eta * cosT) / (c + eta * cosT);
  const C rp = (eta * c - cosT) / (eta * c + cosT);
  return 0.5 * (std::norm(rs) + std::norm(rp));
}

TEST(Conductor, FresnelAgainstClosedForms) {
  for (float n : {0.2f, 0.47f, 1.0f, 1.5f, 2.9f})
    for (float k : {0.0f, 0.01f, 0.5f, 3.0f, 8.0f}) {
      // normal incidence: ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2)
      EXPECT_NEAR(fresnelConductor(1.0f, n, k),
                  ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), 2e-6);
      EXPECT_NEAR(fresnelConductor(0.0f, n, k), 1.0, 1e-6); // grazing
      for (double c : {0.05, 0.2, 0.5, 0.8, 0.99})
        EXPECT_NEAR(fresnelConductor(static_cast<float>(c), n, k), fresnelReference(c, n, k), 2e-5)
            << "n " << n << " k " << k << " cos " << c;
    }
  // k = 0 is a dielectric interface
  for (float c : {0.1f, 0.4f, 0.9f})
    EXPECT_NEAR(fresnelConductor(c, 1.5f, 0), fresnelDielectric(c, 1.5f), 1e-6);
}

// D is normalised over projected area (integral D cos(h) = 1) and the visible normals seen from
// any direction integrate to 1 (which checks G1 against D), isotropic and anisotropic.
TEST(Conductor, GgxNormalisations) {
  for (const auto& [ax, ay] :
       {std::pair{0.1f, 0.1f}, std::pair{0.5f, 0.5f}, std::pair{0.2f, 0.8f}}) {
    const GgxDistribution g{ax, ay};
    const Vec3 wo = normalize(Vec3(0.5f, -0.3f, 0.6f));
    double projected = 0, visible = 0;
    const int nt = 2000, np = 400;
    for (int i = 0; i < nt; ++i)
      for (int j = 0; j < np; ++j) {
        const double th = (i + 0.5) / nt * (kPi / 2), ph = (j + 0.5) / np * 2 * kPi;
        const Vec3 h(static_cast<float>(std::sin(th) * std::cos(ph)),
                     static_cast<float>(std::sin(th) * std::sin(ph)),
                     static_cast<float>(std::cos(th)));
        const double dw = std::sin(th) * (kPi / 2 / nt) * (2 * kPi / np);
        projected += g.d(h) * h.z * dw;
        visible += g.visibleNormalPdf(wo, h) * dw;
      }
    EXPECT_NEAR(projected, 1.0, 2e-3) << ax << " " << ay;
    EXPECT_NEAR(visible, 1.0, 2e-3) << ax << " " << ay;
  }
}

Material conductorMaterial(float ax, float ay, double eta, double k) {
  Material m;
  m.kind = MaterialKind::Conductor;
  m.reflectance = Spectrum(ConstantSpectrum{1.0});
  m.conductorEta = Spectrum(ConstantSpectrum{eta});
  m.conductorK = Spectrum(ConstantSpectrum{k});
  m.alphaU = ax;
  m.alphaV = ay;
  return m;
}

// Sampled directions follow pdf(wi) (chi-square over the sphere; samples lost below the
// surface are the density's missing mass), isotropic and anisotropic, oriented by a tangent.
TEST(Conductor, SamplingFollowsItsPdf) {
  const SampledWavelengths l = test::laneWavelengths();
  const Vec3 ng(0, 0, 1);
  for (const auto& [ax, ay] :
       {std::pair{0.3f, 0.3f}, std::pair{0.6f, 0.6f}, std::pair{0.15f, 0.6f}})
    for (const Vec3& wo :
         {normalize(Vec3(0.3f, -0.2f, 0.9f)), normalize(Vec3(-0.9f, 0.1f, 0.25f))}) {
      const Material m = conductorMaterial(ax, ay, 0.2, 3.0);
      SurfaceBsdf bsdf(m, l, SampledSpectrum::filled(1.0f), ng, wo);
      bsdf.orient(Vec3(1, 1, 0.3f));
      expectDirectionsFollowPdf(
          [&](Sample2 u) {
            BsdfSample s;
            return bsdf.sample(0.5f, u, s) ? s.wi : Vec3(0, 0, 0);
          },
          [&](const Vec3& wi) { return bsdf.pdf(wi); });
    }
}

// GGX's directional albedo with F = 1 by quadrature of the model's formula, written here
// independently: D = a^2 / (pi cos^4 (a^2 + tan^2)^2), Lambda = (sqrt(1 + a^2 tan^2) - 1) / 2.
double ggxAlbedoQuadrature(double a, double cosO) {
  auto lambda = [a](double c) {
    const double t2 = (1 - c * c) / (c * c);
    return 0.5 * (std::sqrt(1 + a * a * t2) - 1);
  };
  const double sinO = std::sqrt(1 - cosO * cosO);
  double e = 0;
  const int nt = 1500, np = 600;
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < np; ++j) {
      const double th = (i + 0.5) / nt * (kPi / 2), ph = (j + 0.5) / np * 2 * kPi;
      const double ix = std::sin(th) * std::cos(ph), iy = std::sin(th) * std::sin(ph),
                   iz = std::cos(th);
      double hx = ix + sinO, hy = iy, hz = iz + cosO;
      const double hl = std::sqrt(hx * hx + hy * hy + hz * hz);
      hz /= hl;
      const double t2 = (1 - hz * hz) / (hz * hz);
      const double d = a * a / (kPi * hz * hz * hz * hz * (a * a + t2) * (a * a + t2));
      const double g2 = 1 / (1 + lambda(cosO) + lambda(iz));
      e += d * g2 / (4 * cosO) * std::sin(th) * (kPi / 2 / nt) * (2 * kPi / np);
    }
  return e;
}

// The white furnace: with F = 1 (k = 1000) the mean sample weight is the albedo, equal to the
// quadrature of f cos; what is missing from 1 is the energy single scattering loses (printed).
TEST(Conductor, WhiteFurnaceAlbedoMatchesQuadrature) {
  const SampledWavelengths l = test::laneWavelengths();
  for (float a : {0.1f, 0.5f, 1.0f})
    for (double cosO : {1.0, 0.5, 0.15}) {
      const Vec3 wo(static_cast<float>(std::sqrt(1 - cosO * cosO)), 0, static_cast<float>(cosO));
      const Material m = conductorMaterial(a, a, 1.0, 1000.0);
      const SurfaceBsdf bsdf(m, l, SampledSpectrum::filled(1.0f), Vec3(0, 0, 1), wo);
      test::RunningStats s;
      for (uint32_t i = 0; i < 200000; ++i) {
        BsdfSample b;
        s.add(bsdf.sample(0.5f, uniform2(i), b) ? b.weight[0] : 0.0);
      }
      const double expected = ggxAlbedoQuadrature(a, cosO);
      EXPECT_NEAR(s.mean, expected, 5 * s.standardError() + 2e-3)
          << "alpha " << a << " cos " << cosO;
      EXPECT_LE(s.mean, 1.0);
      std::printf("GGX albedo (F = 1), alpha %.2f, cos %.2f: %.4f (quadrature %.4f), loss %.1f%%\n",
                  a, cosO, s.mean, expected, 100 * (1 - expected));
    }
}

// f(wo, wi) = f(wi, wo): f cos(wi) / cos(wi) is symmetric.
TEST(Conductor, Reciprocity) {
  const SampledWavelengths l = test::laneWavelengths();
  const Material m = conductorMaterial(0.2f, 0.5f, 0.3, 2.5);
  const Vec3 ng(0, 0, 1), tangent(1, 0.4f, 0);
  for (uint32_t i = 0; i < 200; ++i) {
    const Sample2 u1 = uniform2(2 * i), u2 = uniform2(2 * i + 1);
    auto dir = [](Sample2 u) {
      const float z = 0.05f + 0.95f * u.u, r = std::sqrt(1 - z * z),
                  p = 2 * static_cast<float>(kPi) * u.v;
      return Vec3(r * std::cos(p), r * std::sin(p), z);
    };
    const Vec3 a = dir(u1), b = dir(u2);
    SurfaceBsdf fa(m, l, SampledSpectrum::filled(1.0f), ng, a),
        fb(m, l, SampledSpectrum::filled(1.0f), ng, b);
    fa.orient(tangent);
    fb.orient(tangent);
    const float x = fa.f(b)[0] / b.z, y = fb.f(a)[0] / a.z;
    EXPECT_NEAR(x, y, 1e-4f * std::max(1.0f, std::abs(x)));
  }
}

// Anisotropy follows the tangent: swapping alpha_u and alpha_v equals turning the tangent by 90
// degrees; an isotropic lobe ignores the tangent.
TEST(Conductor, AnisotropyFollowsTheTangent) {
  const SampledWavelengths l = test::laneWavelengths();
  const Vec3 ng(0, 0, 1), wo = normalize(Vec3(0.4f, 0.3f, 0.8f)),
                          wi = normalize(Vec3(-0.2f, -0.6f, 0.7f));
  const Material uv = conductorMaterial(0.1f, 0.6f, 0.3, 2.5),
                 vu = conductorMaterial(0.6f, 0.1f, 0.3, 2.5);
  SurfaceBsdf a(uv, l, SampledSpectrum::filled(1.0f), ng, wo);
  SurfaceBsdf b(vu, l, SampledSpectrum::filled(1.0f), ng, wo);
  a.orient(Vec3(1, 0, 0));
  b.orient(Vec3(0, 1, 0));
  EXPECT_NEAR(a.f(wi)[0], b.f(wi)[0], 1e-5f * a.f(wi)[0]);
  SurfaceBsdf c(uv, l, SampledSpectrum::filled(1.0f), ng, wo);
  c.orient(Vec3(0, 1, 0));
  EXPECT_GT(std::abs(a.f(wi)[0] - c.f(wi)[0]), 0.1f * a.f(wi)[0]);
}

// The built-in metals: Johnson & Christy's table points and its interpolation; aluminium's
// Lorentz-Drude model against the measured values of Hagemann, Gudat & Kunz (1974, Table 3) to
// 15% in n and 3% in k over the visible (two different measurements).
TEST(Conductor, MeasuredMetals) {
  const auto gold = namedMetal("gold");
  ASSERT_TRUE(gold);
  EXPECT_NEAR(gold->eta(1239.84193 / 2.5), 1.04, 1e-9);
  EXPECT_NEAR(gold->k(1239.84193 / 2.5), 1.833, 1e-9);
  const double mid = 0.5 * (1239.84193 / 2.5 + 1239.84193 / 2.38);
  EXPECT_NEAR(gold->eta(mid), 0.5 * (1.04 + 0.62), 1e-9);
  EXPECT_NEAR(namedMetal("silver")->k(1239.84193 / 3.0), 2.275, 1e-9);
  EXPECT_NEAR(namedMetal("copper")->eta(1239.84193 / 2.01), 0.30, 1e-9);
  struct Point {
    double nm, n, k;
  };
  for (const Point p :
       {Point{413.3, 0.548, 5.00}, Point{495.9, 0.771, 5.91}, Point{619.9, 1.292, 7.28}}) {
    double n = 0, k = 0;
    aluminiumIndex(p.nm, n, k);
    EXPECT_NEAR(n, p.n, 0.15 * p.n) << p.nm;
    EXPECT_NEAR(k, p.k, 0.03 * p.k) << p.nm;
  }
  EXPECT_FALSE(namedMetal("Gold"));
  EXPECT_EQ(metalNames().size(), 4u);
}

// A smooth gold sphere under a uniform background of 1, seen along its axis: every band reads
// the normal-incidence reflectance ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2) of the table.
// (16 x 16 pixels at 64 spp, not 4 x 4 at 1024: the z-test over pixels needs enough of them
// for its standard error; expectBands.)
TEST(Conductor, SmoothGoldAtNormalIncidence) {
  const RenderOutput out = renderText(sceneText(
      "<xres>16</xres><yres>16</yres><mode>spectral_mcpt</mode><depth>3</depth><sampl>64</sampl>"
      "<background>1</background>",
      "<position>0,0,-100</position><look_at>0,0,0</look_at><fov>0.02</fov>",
      "<sphere><center>0,0,0</center><radius>1</radius><material>conductor</material>"
      "<metal>gold</metal></sphere>"));
  const MetalIndex gold = *namedMetal("gold");
  std::vector<double> nm, v;
  for (double l = 350; l <= 850; l += 0.25) {
    const double n = gold.eta(l), k = gold.k(l);
    nm.push_back(l);
    v.push_back(((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k));
  }
  const Spectrum r(TabulatedSpectrum{nm, v});
  expectBands(
      out.film, [&](int b) { return bandAverage(r, out.film.bands(), b); }, 0.01, {}, "gold");
}

// Objects differing only in their conductor parameters (metal, eta/k, alpha, coating) get
// materials of their own (inline materials written alike are shared).
TEST(Conductor, DistinctParametersAreDistinctMaterials) {
  const std::string s = "<sphere><center>0,0,0</center><radius>1</radius><material>conductor"
                        "</material>";
  const RenderScene scene = resolveRenderScene(parseScene(
      sceneText("<xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode>",
                "<position>0,0,-5</position><look_at>0,0,0</look_at>",
                s + "<metal>gold</metal></sphere>" + s + "<metal>silver</metal></sphere>" + s +
                    "<metal>gold</metal><alpha>0.2</alpha></sphere>" + s +
                    "<metal>gold</metal><alpha_u>0.2</alpha_u><alpha_v>0.1</alpha_v></sphere>" + s +
                    "<eta>1</eta><k>2</k></sphere>" + s + "<eta>1</eta><k>3</k></sphere>" + s +
                    "<metal>gold</metal><coating><thickness>100</thickness><ior>1.4</ior>"
                    "</coating></sphere>" +
                    s +
                    "<metal>gold</metal><coating><thickness>120</thickness><ior>1.4</ior>"
                    "</coating></sphere>" +
                    s + "<metal>gold</metal></sphere>"),
      "t.scn"));
  EXPECT_EQ(scene.materials.size(), 8u); // the last sphere shares the first's
  EXPECT_NE(scene.materials[0].conductorK(500), scene.materials[1].conductorK(500));
}

TEST(Conductor, SceneErrors) {
  const auto error = test::sphereSceneError;
  EXPECT_NE(error("<material>conductor</material><metal>tin</metal>")
                .find("expected a metal name (gold, silver, copper, aluminium), found 'tin'"),
            std::string::npos);
  EXPECT_NE(error("<material>conductor</material><eta>0.2</eta>").find("found <eta> alone"),
            std::string::npos);
  EXPECT_NE(error("<material>conductor</material><metal>gold</metal><reflectance>0.5</reflectance>")
                .find("on conductor, found <reflectance> (its colour is its <metal>"),
            std::string::npos);
  EXPECT_NE(error("<material>conductor</material><metal>gold</metal><eta>1</eta><k>2</k>")
                .find("either <metal> or <eta> and <k>, found both"),
            std::string::npos);
  EXPECT_NE(error("<material>conductor</material><eta>0</eta><k>2</k>").find("expected eta within"),
            std::string::npos);
  EXPECT_NE(error("<material>conductor</material><metal>gold</metal><alpha>1.5</alpha>")
                .find("a GGX roughness alpha in [0, 1]"),
            std::string::npos);
  EXPECT_NE(error("<material>conductor</material><metal>gold</metal><alpha_u>0.1</alpha_u>")
                .find("<alpha_u> and <alpha_v> together"),
            std::string::npos);
  EXPECT_NE(error("<material>matte</material><reflectance>0.5</reflectance><alpha>0.1</alpha>")
                .find("on matte, found <alpha> (GGX roughness is for conductors and dielectrics"),
            std::string::npos);
}

} // namespace
} // namespace nx
