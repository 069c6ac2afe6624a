// Emitting media (source sigma_a Le) against closed forms: the equilibrium of an infinite
// medium of any albedo (L = Le, reproduced exactly by a finite sphere under a background of
// Le), the infinite limit of a deep sphere under a black sky, and an emitting absorber seen
// along a chord (L = Le (1 - exp(-sigma_a d))).

#include <gtest/gtest.h>

#include <cmath>

#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "spectra/bands.h"
#include "support/errors.h"
#include "support/render_checks.h"

namespace nx {
namespace {

const std::string kLe = "400:1, 700:3"; // emitted radiance, linear in between
const std::string kCentreCamera = "<position>0,0,0</position><look_at>0,0,1</look_at><fov>60</fov>";
// Far away with a tiny field of view: every pixel looks along a diameter.
const std::string kFarCamera = "<position>0,0,-100</position><look_at>0,0,0</look_at>"
                               "<fov>0.02</fov>";

std::string settings(const std::string& background, int spp) {
  return "<xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>3</depth><sampl>" +
         std::to_string(spp) + "</sampl><background extrapolate=\"hold\">" + background +
         "</background>";
}

std::string glowingSphere(double radius, const std::string& sigmaA, const std::string& sigmaS,
                          double g) {
  return "<sphere><center>0,0,0</center><radius>" + std::to_string(radius) +
         "</radius><material>interface</material><medium><sigma_a extrapolate=\"hold\">" + sigmaA +
         "</sigma_a><sigma_s extrapolate=\"hold\">" + sigmaS + "</sigma_s><g>" + std::to_string(g) +
         "</g><emission extrapolate=\"hold\">" + kLe + "</emission></medium></sphere>";
}

// The band averages of Le(nm) times f(nm).
std::function<double(int)> leBands(const Film& film, const std::function<double(double)>& f) {
  std::vector<double> nm, v;
  for (double l = 380; l <= 720; l += 0.05) {
    const double le = 1 + 2 * (std::clamp(l, 400.0, 700.0) - 400) / 300;
    nm.push_back(l);
    v.push_back(le * f(l));
  }
  const Spectrum s(TabulatedSpectrum{nm, v});
  return [s, &film](int b) { return bandAverage(s, film.bands(), b); };
}

// In an infinite homogeneous medium emitting sigma_a Le, the transport equation's uniform
// solution is L = sigma_a Le / (sigma_t - sigma_s) = Le for any albedo and phase function. A
// finite sphere under a background of Le is indistinguishable from it: every pixel reads Le,
// camera inside or outside, with chromatic coefficients (spectral MIS between lanes), albedos
// from 0.13 to 0.87, forward and backward scattering.
TEST(EmittingMedia, EquilibriumReadsLeForAnyAlbedo) {
  const std::string camera = "<position>0,0,-4</position><look_at>0,0,0</look_at><fov>40</fov>";
  for (double g : {0.0, 0.8, -0.5})
    for (const std::string& cam : {camera, kCentreCamera}) {
      const RenderOutput out = renderText(sceneText(
          settings(kLe, 512), cam, glowingSphere(1.0, "400:0.5, 700:2", "400:3, 700:0.3", g)));
      expectBands(out.film, leBands(out.film, [](double) { return 1.0; }), 0.01, {},
                  "g " + std::to_string(g));
      EXPECT_EQ(out.stats.nonFinite, 0u);
    }
}

// The infinite limit: a sphere of optical radius sigma_t R = 40 and albedo 1/2 under a black
// sky. Radiance escaping from the centre would have to cross 40 mean free paths with
// survival 1/2 per collision (below 1e-9), so the centre reads Le.
TEST(EmittingMedia, DeepSphereReadsTheInfiniteMediumRadiance) {
  const RenderOutput out =
      renderText(sceneText(settings("0", 256), kCentreCamera, glowingSphere(20.0, "1", "1", 0.3)));
  expectBands(out.film, leBands(out.film, [](double) { return 1.0; }), 0.01, {}, "deep");
}

// Without scattering, the radiance along a chord of length d through an emitting absorber
// under a black sky is Le (1 - exp(-sigma_a d)): from the centre d = R, through the diameter
// d = 2R; sigma_a chromatic (0.2 to 1.5 per unit length).
TEST(EmittingMedia, EmittingAbsorberAlongAChord) {
  auto sigmaA = [](double nm) { return 0.2 + 1.3 * (std::clamp(nm, 400.0, 700.0) - 400) / 300; };
  const std::string body = glowingSphere(1.0, "400:0.2, 700:1.5", "0", 0);
  const RenderOutput centre = renderText(sceneText(settings("0", 1024), kCentreCamera, body));
  expectBands(centre.film,
              leBands(centre.film, [&](double nm) { return 1 - std::exp(-sigmaA(nm)); }), 0.01, {},
              "centre");
  const RenderOutput through = renderText(sceneText(settings("0", 1024), kFarCamera, body));
  expectBands(through.film,
              leBands(through.film, [&](double nm) { return 1 - std::exp(-2 * sigmaA(nm)); }), 0.01,
              {}, "diameter");
}

TEST(EmittingMedia, Errors) {
  auto error = [](const std::string& medium) {
    return test::errorMessage([&] {
      (void)resolveRenderScene(
          parseScene(sceneText(settings("0", 4), kFarCamera,
                               "<sphere><center>0,0,0</center><radius>1</radius><material>interface"
                               "</material><medium>" +
                                   medium + "</medium></sphere>"),
                     "t.scn"));
    });
  };
  EXPECT_NE(error("<sigma_a>0</sigma_a><sigma_s>1</sigma_s><emission>1</emission>")
                .find("t.scn:1: expected a medium that absorbs (sigma_a > 0 somewhere in"),
            std::string::npos);
  EXPECT_NE(error("<sigma_a>1</sigma_a><sigma_s>1</sigma_s><emission>-1</emission>")
                .find("t.scn:1: expected"),
            std::string::npos);
  EXPECT_NE(error("<sigma_a>1</sigma_a><sigma_s>1</sigma_s><emission scale=\"-1\">1</emission>")
                .find("a non-negative emission scale, found '-1'"),
            std::string::npos);
  EXPECT_NE(error("<sigma_a scale=\"-2\">1</sigma_a><sigma_s>1</sigma_s>")
                .find("a positive coefficient scale, found '-2'"),
            std::string::npos);
  EXPECT_NE(error("<sigma_a>water:absorbtion</sigma_a><sigma_s>1</sigma_s>")
                .find("expected water:absorption, water:scattering (per metre), a reflectance "
                      "name"),
            std::string::npos);
}

} // namespace
} // namespace nx
