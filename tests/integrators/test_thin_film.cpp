// Thin-film coatings against the characteristic-matrix method (an independent formulation of
// the same optics), closed forms (no film, a quarter-wave anti-reflection layer) and renders of
// a coated conductor at normal and oblique incidence, per band.

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "integrators/materials/fresnel.h"
#include "integrators/renderer.h"
#include "spectra/bands.h"
#include "support/errors.h"
#include "support/material_checks.h"
#include "support/render_checks.h"

namespace nx {
namespace {

using C = std::complex<double>;

// Reflectance of one film by the characteristic matrix (Born & Wolf sec. 1.6; Macleod, "Thin-
// Film Optical Filters", ch. 2): [B, C] = M [1, y2], M = [[cos d, i sin d / y1], [i y1 sin d,
// cos d]], r = (y0 B - C) / (y0 B + C), with tilted admittances y = n cos(theta) (s) and
// y = n / cos(theta) (p), averaged over the two polarisations. The matrix method's waves are
// exp(i (w t - k z)), in which an absorbing index is n - i k: the substrate enters conjugated
// (the renderer's n + i k belongs to exp(i (k z - w t))).
double matrixReflectance(double cos0, double n0, double n1, C n2, double d, double lambda) {
  n2 = std::conj(n2);
  const double s = n0 * std::sqrt(1 - cos0 * cos0); // n sin(theta), the same in every layer
  auto cosIn = [s](C n) { return std::sqrt(C(1) - (s / n) * (s / n)); };
  // cos(theta_2) with Im(n2 cos(theta_2)) <= 0: the wave decays into the substrate
  const C c1 = cosIn(C(n1)), c2 = std::conj(std::sqrt(std::conj(n2 * n2) - s * s)) / n2;
  const C delta = 2 * kPi * n1 * d * c1 / lambda;
  double r2 = 0;
  for (int p = 0; p < 2; ++p) {
    const C y0 = p ? n0 / cos0 : n0 * cos0, y1 = p ? n1 / c1 : n1 * c1, y2 = p ? n2 / c2 : n2 * c2;
    const C b = std::cos(delta) + C(0, 1) * std::sin(delta) / y1 * y2;
    const C c = C(0, 1) * y1 * std::sin(delta) + std::cos(delta) * y2;
    r2 += std::norm((y0 * b - c) / (y0 * b + c));
  }
  return r2 / 2;
}

TEST(ThinFilm, AiryAgreesWithTheCharacteristicMatrix) {
  for (const C n2 : {C(0.2, 3.0), C(1.5, 0), C(0.47, 2.4), C(2.4, 0)})
    for (double d : {0.0, 100.0, 250.0, 1200.0})
      for (double cos0 : {1.0, 0.8, 0.5, 0.2})
        for (double lambda : {380.0, 450.0, 550.0, 700.0, 900.0}) {
          const double expected = matrixReflectance(cos0, 1.0, 1.38, n2, d, lambda);
          EXPECT_NEAR(thinFilmReflectance(static_cast<float>(cos0), 1.0f, 1.38f,
                                          static_cast<float>(n2.real()),
                                          static_cast<float>(n2.imag()), static_cast<float>(d),
                                          static_cast<float>(lambda)),
                      expected, 2e-5)
              << n2 << " d " << d << " cos " << cos0 << " lambda " << lambda;
        }
  // No film: the substrate's Fresnel reflectance.
  for (float cos0 : {1.0f, 0.6f, 0.1f})
    EXPECT_NEAR(thinFilmReflectance(cos0, 1, 1.38f, 0.2f, 3.0f, 0, 500),
                fresnelConductor(cos0, 0.2f, 3.0f), 1e-5);
  // A quarter-wave layer of index sqrt(1.5) on glass cancels the reflection at normal
  // incidence at lambda = 4 n1 d.
  const double n1 = std::sqrt(1.5), d = 550 / (4 * n1);
  EXPECT_NEAR(
      thinFilmReflectance(1, 1, static_cast<float>(n1), 1.5f, 0, static_cast<float>(d), 550), 0.0,
      1e-6);
  EXPECT_GT(thinFilmReflectance(1, 1, static_cast<float>(n1), 1.5f, 0, static_cast<float>(d), 400),
            1e-3);
}

// The case: a 250 nm film of n = 1.38 on a conductor of eta 0.2, k 3.0 under a uniform
// background of 1, seen in the mirror direction at normal incidence (a sphere along its axis)
// and at 60 degrees (a plane): every band reads the band average of the Airy reflectance.
// (16 x 16 pixels at 64 spp, not 4 x 4 at 1024: the z-test over pixels needs enough of them
// for its standard error; expectBands.)
TEST(ThinFilm, CoatedConductorPerBand) {
  const std::string settings =
      "<xres>16</xres><yres>16</yres><mode>spectral_mcpt</mode><depth>3</depth><sampl>64</sampl>"
      "<background>1</background>";
  const std::string metal = "<material>conductor</material><eta>0.2</eta><k>3</k>"
                            "<coating><thickness>250</thickness><ior>1.38</ior></coating>";
  const RenderOutput normal = renderText(
      sceneText(settings, "<position>0,0,-100</position><look_at>0,0,0</look_at><fov>0.02</fov>",
                "<sphere><center>0,0,0</center><radius>1</radius>" + metal + "</sphere>"));
  const RenderOutput oblique = renderText(sceneText(
      settings, "<position>0,50,-86.6025404</position><look_at>0,0,0</look_at><fov>0.02</fov>",
      "<plane><normal>0,1,0</normal><distance>0</distance>" + metal + "</plane>"));
  for (const auto& [out, cos0] : {std::pair{&normal, 1.0}, std::pair{&oblique, 0.5}}) {
    std::vector<double> nm, v;
    for (double l = 350; l <= 850; l += 0.25) {
      nm.push_back(l);
      v.push_back(matrixReflectance(cos0, 1, 1.38, C(0.2, 3.0), 250, l));
    }
    const Spectrum r(TabulatedSpectrum{nm, v});
    expectBands(
        out->film, [&](int b) { return bandAverage(r, out->film.bands(), b); }, 0.01, {},
        "cos " + std::to_string(cos0));
  }
}

// A coated glass surface: a glass plane seen at 45 degrees under a background of 1, with a
// black floor below it, reads the reflectance of its coated top face (what is refracted into
// the glass ends on the floor). The hero reflects with probability R (about 2%), so this needs
// many samples.
TEST(ThinFilm, CoatedGlassReflectance) {
  const std::string settings =
      "<xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>2</depth><sampl>8192</sampl>"
      "<background>1</background>";
  const double d = 100, n1 = 1.38;
  const RenderOutput out = renderText(sceneText(
      settings,
      "<position>0,70.7106781,-70.7106781</position><look_at>0,0,0</look_at><fov>0.02</fov>",
      "<plane><normal>0,1,0</normal><distance>0</distance><material>glass</material>"
      "<coating><thickness>100</thickness><ior>1.38</ior></coating></plane>"
      "<plane><normal>0,1,0</normal><distance>-1</distance><material>matte</material>"
      "<reflectance>0</reflectance></plane>"));
  std::vector<double> nm, v;
  for (double l = 350; l <= 850; l += 0.25) {
    nm.push_back(l);
    v.push_back(matrixReflectance(std::sqrt(0.5), 1, n1, C(1.5, 0), d, l));
  }
  const Spectrum r(TabulatedSpectrum{nm, v});
  expectBands(
      out.film, [&](int b) { return bandAverage(r, out.film.bands(), b); }, 0.03, {},
      "coated glass");
}

TEST(ThinFilm, SceneErrors) {
  const auto error = test::sphereSceneError;
  EXPECT_NE(
      error("<material>matte</material><reflectance>0.5</reflectance><coating><thickness>100"
            "</thickness><ior>1.4</ior></coating>")
          .find("on matte, found <coating> (thin films lie on conductors and smooth dielectrics)"),
      std::string::npos);
  EXPECT_NE(error("<material>conductor</material><metal>gold</metal><coating><ior>1.4</ior>"
                  "</coating>")
                .find("expected <thickness> inside <coating>, found none"),
            std::string::npos);
  EXPECT_NE(error("<material>conductor</material><metal>gold</metal><coating><thickness>-5"
                  "</thickness><ior>1.4</ior></coating>")
                .find("a coating thickness in nm in (0, 100000]"),
            std::string::npos);
}

} // namespace
} // namespace nx
