// Participating media against closed forms: Beer-Lambert through index-matched and glass
// spheres (camera outside and inside), a scattering furnace, nesting, and scene errors.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "spectra/bands.h"
#include "support/errors.h"
#include "support/render_checks.h"

namespace nx {
namespace {

const std::string kBackground =
    "<xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>3</depth><sampl>1024</sampl>"
    "<background>1</background>";
// Far away with a tiny field of view: every pixel looks along a diameter (to 4e-8 in length).
const std::string kFarCamera = "<position>0,0,-100</position><look_at>0,0,0</look_at>"
                               "<fov>0.02</fov>";
const std::string kCentreCamera = "<position>0,0,0</position><look_at>0,0,1</look_at><fov>60</fov>";
const std::string kSigmaA = "400:0.2, 700:1.5"; // per unit length, linear in between

// (held constant beyond 400-700 nm: extrapolate="hold")
double sigmaA(double nm) {
  return 0.2 + 1.3 * (std::clamp(nm, 400.0, 700.0) - 400) / 300;
}

// The band averages of f(sigma_a(nm)) over the bands of a film.
std::function<double(int)> bandsOf(const Film& film, const std::function<double(double)>& f) {
  std::vector<double> nm, v;
  for (double l = 380; l <= 720; l += 0.05) nm.push_back(l), v.push_back(f(sigmaA(l)));
  const Spectrum s(TabulatedSpectrum{nm, v});
  return [s, &film](int b) { return bandAverage(s, film.bands(), b); };
}

std::string absorbingSphere(const std::string& material, double radius) {
  return "<sphere><center>0,0,0</center><radius>" + std::to_string(radius) + "</radius><material>" +
         material + "</material><medium><sigma_a extrapolate=\"hold\">" + kSigmaA +
         "</sigma_a><sigma_s>0</sigma_s></medium></sphere>";
}

// Beer-Lambert: through the diameter of an index-matched absorbing sphere of radius R the
// background of 1 arrives as exp(-2 R sigma_a); from its centre, exp(-R sigma_a).
TEST(Media, BeerLambertThroughIndexMatchedSphere) {
  const RenderOutput through =
      renderText(sceneText(kBackground, kFarCamera, absorbingSphere("interface", 1.0)));
  expectBands(through.film, bandsOf(through.film, [](double s) { return std::exp(-2 * s); }), 0.01,
              {}, "through");
  const RenderOutput inside =
      renderText(sceneText(kBackground, kCentreCamera, absorbingSphere("interface", 1.0)));
  expectBands(inside.film, bandsOf(inside.film, [](double s) { return std::exp(-s); }), 0.01, {},
              "inside");
}

// A glass sphere filled with the absorber, at normal incidence: reflected F, or entered
// (1 - F), attenuated T = exp(-2 R sigma_a) per crossing and reflected F inside at each wall:
// L = F + (1 - F)^2 T / (1 - F T) with F = ((n - 1) / (n + 1))^2. The same with the liquid
// in an index-matched sphere of radius 0.9 nested in a clear glass sphere (T over 1.8).
TEST(Media, AbsorberInsideGlassAtNormalIncidence) {
  const double F = 0.04; // n = 1.5
  auto expected = [F](double length) {
    return [F, length](double s) {
      const double T = std::exp(-length * s);
      return F + (1 - F) * (1 - F) * T / (1 - F * T);
    };
  };
  std::string settings = kBackground;
  settings.replace(settings.find("<sampl>1024"), 11, "<sampl>2048");
  const RenderOutput filled =
      renderText(sceneText(settings, kFarCamera, absorbingSphere("glass", 1.0)));
  expectBands(filled.film, bandsOf(filled.film, expected(2.0)), 0.01, {}, "filled glass");
  const RenderOutput nested = renderText(sceneText(
      settings, kFarCamera,
      "<sphere><center>0,0,0</center><radius>1</radius><material>glass</material></sphere>" +
          absorbingSphere("interface", 0.9)));
  expectBands(nested.film, bandsOf(nested.film, expected(1.8)), 0.01, {}, "nested");
}

// A thin glass wall (thin_glass: reflectance R = 2F / (1 + F) with its internal reflections,
// straight transmission) holding the absorber: at normal incidence the same series as above
// with R for F, L = R + (1 - R)^2 T / (1 - R T); next-event estimation sees through the wall.
// A clear, empty thin_glass sphere in the same background reads 1 everywhere.
TEST(Media, AbsorberInsideThinGlass) {
  const double F = 0.04, R = 2 * F / (1 + F);
  const RenderOutput out =
      renderText(sceneText(kBackground, kFarCamera, absorbingSphere("thin_glass", 1.0)));
  expectBands(out.film,
              bandsOf(out.film,
                      [R](double s) {
                        const double T = std::exp(-2 * s);
                        return R + (1 - R) * (1 - R) * T / (1 - R * T);
                      }),
              0.015, {}, "thin glass");
  const RenderOutput clear = renderText(
      sceneText(kBackground, "<position>0,0,-4</position><look_at>0,0,0</look_at><fov>40</fov>",
                "<sphere><center>0,0,0</center><radius>1</radius><material>thin_glass"
                "</material></sphere>"));
  expectBands(
      clear.film, [](int) { return 1.0; }, 0.01, {}, "clear thin glass");
}

// A scattering furnace: a non-absorbing medium (albedo 1) under a uniform background of 1
// keeps the radiance 1 everywhere, for the camera outside (pixels through and beside the
// sphere) and inside, isotropic and forward scattering, next-event estimation through the
// interface and phase sampling combined by MIS.
TEST(Media, ScatteringFurnaceReadsTheBackground) {
  const std::string settings =
      "<xres>16</xres><yres>16</yres><mode>spectral_mcpt</mode><depth>2</depth><sampl>256</sampl>"
      "<background>1</background>";
  for (const char* g : {"0", "0.7", "-0.4"})
    for (const std::string& camera :
         {std::string("<position>0,0,-4</position><look_at>0,0,0</look_at><fov>40</fov>"),
          kCentreCamera}) {
      const RenderOutput out = renderText(sceneText(
          settings, camera,
          std::string("<sphere><center>0,0,0</center><radius>1</radius><material>interface"
                      "</material><medium><sigma_a>0</sigma_a><sigma_s>400:1, 700:4</sigma_s><g>") +
              g + "</g></medium></sphere>"));
      expectBands(
          out.film, [](int) { return 1.0; }, 0.015, {}, std::string("g ") + g);
      EXPECT_EQ(out.stats.nonFinite, 0u);
    }
}

// Long chromatic paths: sigma_s from 2 to 25 per unit length across the spectrum, seen from
// the sphere's centre: hundreds of scatterings (about (sigma_s R)^2 to escape) whose lanes'
// path densities differ by many orders of magnitude. The furnace still reads 1 and nothing
// overflows (the spectral MIS ratios are renormalised after each flight).
TEST(Media, LongChromaticPathsKeepTheFurnace) {
  const RenderOutput out = renderText(sceneText(
      "<xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>2</depth><sampl>256</sampl>"
      "<background>1</background>",
      kCentreCamera,
      "<sphere><center>0,0,0</center><radius>1</radius><material>interface</material><medium>"
      "<sigma_a>0</sigma_a><sigma_s extrapolate=\"hold\">400:2, 700:25</sigma_s></medium>"
      "</sphere>"));
  EXPECT_EQ(out.stats.nonFinite, 0u);
  expectBands(
      out.film, [](int) { return 1.0; }, 0.04, {}, "chromatic furnace");
}

// Scenes without media run the path tracer without the media code.
TEST(Media, OnlyScenesWithMediaOrInterfacesHaveThem) {
  auto build = [](const std::string& body) {
    return resolveRenderScene(parseScene(sceneText(kBackground, kFarCamera, body), "t.scn"));
  };
  EXPECT_FALSE(build("<sphere><center>0,0,0</center><radius>1</radius><material>glass"
                     "</material></sphere>")
                   .hasMedia);
  EXPECT_TRUE(build(absorbingSphere("glass", 1)).hasMedia);
  EXPECT_TRUE(build("<sphere><center>0,0,0</center><radius>1</radius><material>interface"
                    "</material></sphere>")
                  .hasMedia);
}

TEST(Media, CameraMediaAreTheSpheresAroundIt) {
  const RenderScene scene = resolveRenderScene(parseScene(
      sceneText(kBackground, kCentreCamera,
                "<sphere><center>0,0,0</center><radius>3</radius><material>glass</material>"
                "</sphere>" +
                    absorbingSphere("interface", 2.0) +
                    "<sphere><center>5,0,0</center><radius>1</radius><material>interface"
                    "</material></sphere>"),
      "t.scn"));
  EXPECT_EQ(scene.cameraMedia.depth(), 2);
  EXPECT_EQ(scene.cameraMedia.current(), 0);
}

TEST(Media, SceneErrors) {
  auto error = [](const std::string& body, const std::string& settings = kBackground) {
    return test::errorMessage([&] {
      (void)resolveRenderScene(parseScene(sceneText(settings, kFarCamera, body), "t.scn"));
    });
  };
  EXPECT_EQ(
      error("<plane><normal>0,1,0</normal><distance>0</distance><material>interface"
            "</material><medium><sigma_a>1</sigma_a><sigma_s>0</sigma_s></medium></plane>"),
      "t.scn:1: expected one of <material>, <color>, <reflectance>, <roughness>, <ior>, "
      "<fluorescence>, <eta>, <k>, <metal>, <alpha>, <alpha_u>, <alpha_v>, <sigma>, <coating>, "
      "<emission>, <normal>, <distance> inside <plane>, found <medium>");
  EXPECT_EQ(error("<sphere><center>0,0,0</center><radius>1</radius><material>interface"
                  "</material><reflectance>0.5</reflectance></sphere>"),
            "t.scn:1: expected no parameters on interface, found <reflectance> (it only bounds a "
            "medium)");
  EXPECT_EQ(error("<sphere><center>0,0,0</center><radius>1</radius><material>interface"
                  "</material><emission>1</emission></sphere>"),
            "t.scn:1: expected no <emission> on an interface (it only bounds a medium), found one");
  EXPECT_EQ(error("<sphere><center>0,0,0</center><radius>1</radius><material>interface"
                  "</material><medium><sigma_a>400:1, 700:-1</sigma_a><sigma_s>0</sigma_s>"
                  "</medium></sphere>")
                .substr(0, 40),
            "t.scn:1: expected sigma_a within [0, 1e+");
  EXPECT_NE(error("<sphere><center>0,0,0</center><radius>1</radius><material>interface"
                  "</material><medium><sigma_a>0</sigma_a><sigma_s>0</sigma_s><g>1</g></medium>"
                  "</sphere>")
                .find("expected a Henyey-Greenstein g (mean cosine) in [-0.999, 0.999]"),
            std::string::npos);
  EXPECT_NE(error("<sphere><center>0,0,0</center><radius>1</radius><material>interface"
                  "</material><medium><sigma_s>0</sigma_s></medium></sphere>")
                .find("expected <sigma_a> inside <medium>"),
            std::string::npos);
  EXPECT_NE(error("<sphere><center>0,0,0</center><radius>1</radius><material>interface"
                  "</material><medium><sigma_a>0</sigma_a><sigma_s>0</sigma_s><fluorescence>"
                  "<absorption>350</absorption><stokes>100</stokes></fluorescence></medium>"
                  "</sphere>")
                .find("expected a <peak> (the dye's peak absorption coefficient per unit "
                      "length) in a medium's <fluorescence>"),
            std::string::npos);
  EXPECT_NE(error("<sphere><center>0,0,0</center><radius>1</radius><material>interface"
                  "</material><medium><sigma_a>0</sigma_a><sigma_s>0</sigma_s><fluorescence>"
                  "<matrix>m.csv</matrix></fluorescence></medium></sphere>")
                .find("expected the parametric model in a medium's <fluorescence>"),
            std::string::npos);
  EXPECT_EQ(error("<sphere><center>0,0,0</center><radius>1</radius><material>interface"
                  "</material><medium><sigma_a>0</sigma_a><sigma_s>0</sigma_s><fluorescence>"
                  "<absorption>350</absorption><stokes>100</stokes><peak>50</peak>"
                  "</fluorescence></medium></sphere>"),
            "no error"); // a peak coefficient above 1 is fine in a medium
  std::string rt = kBackground;
  rt.replace(rt.find("spectral_mcpt"), 13, "rt");
  EXPECT_NE(error(absorbingSphere("interface", 1), rt)
                .find("expected <mode> spectral_mcpt or mcpt for a scene with media"),
            std::string::npos);
}

} // namespace
} // namespace nx

namespace nx {
namespace {

// A fluorescent, non-scattering medium filling an index-matched sphere of radius R under a
// background Le = 1 below 420 nm (0 above: what the camera sees in the emission band is
// re-emitted light alone), seen from the centre. With sigma_f = peak a (the dye's
// absorption per 5 nm bin) and the matrix M of the model (peak absorptance 1), the radiance
// at the centre in emission bin o is, to first order in the re-emission,
//   L_o = Le_o exp(-sigma_f,o R)
//       + sum_{i<o} peak M[i][o] integral_0^R exp(-sigma_f,o s) psi_i(s) ds,
//   psi_i(s) = Le_i / 2 integral_-1^1 exp(-sigma_f,i l(s, mu)) dmu,
//   l = -s mu + sqrt(R^2 - s^2 (1 - mu^2)),
// psi_i the fluence at radius s over 4 pi (the background seen through the dye). Light
// re-emitted once and absorbed again (second order) is bounded below 0.3% here: the
// emission lies 170 nm above a narrow absorption band.
TEST(Media, FluorescentSphereMatchesTheFirstOrderIntegral) {
  const double R = 1, peak = 4;
  FluorescenceModel model;
  model.absorptionPeakNm = 380;
  model.stokesNm = 170;
  model.widthNm = 5;
  model.skew = 0;
  model.quantumYield = 0.5;
  model.peakAbsorptance = 1;
  const ReradiationMatrix M = ReradiationMatrix::fromModel(model);
  constexpr int kBins = ReradiationMatrix::kBins;
  const int nS = 300, nMu = 300;
  std::vector<double> psi(static_cast<size_t>(kBins) * nS, 0.0);
  auto background = [](int bin) { return ReradiationMatrix::centre(bin) < 420 ? 1.0 : 0.0; };
  for (int i = 0; i < kBins; ++i) {
    const double sf = peak * M.absorptance(i);
    for (int k = 0; k < nS; ++k) {
      const double s = (k + 0.5) / nS * R;
      double sum = 0;
      for (int m = 0; m < nMu; ++m) {
        const double mu = -1 + 2 * (m + 0.5) / nMu;
        sum += std::exp(-sf * (-s * mu + std::sqrt(R * R - s * s * (1 - mu * mu))));
      }
      psi[static_cast<size_t>(i) * nS + k] = background(i) * sum / nMu; // (1/2) integral
    }
  }
  std::vector<double> L(kBins, 0.0);
  double secondOrderBound = 0;
  for (int o = 0; o < kBins; ++o) {
    const double sfo = peak * M.absorptance(o);
    double fl = 0;
    for (int i = 0; i < o; ++i) {
      if (M(i, o) == 0) continue;
      double integral = 0;
      for (int k = 0; k < nS; ++k)
        integral += std::exp(-sfo * (k + 0.5) / nS * R) * psi[static_cast<size_t>(i) * nS + k];
      fl += peak * M(i, o) * integral * R / nS;
    }
    L[static_cast<size_t>(o)] = background(o) * std::exp(-sfo * R) + fl;
    if (ReradiationMatrix::centre(o) > 450) secondOrderBound += fl * sfo * R;
  }
  // All light re-absorbed after its first re-emission (an upper bound: every path taken as
  // long as R), re-emitted into bin o with at most the share max_i M[i][o] / a_i = Q e_o
  // l_i / l_o, against the radiance in the emission band.
  double share = 0;
  for (int i = 0; i < kBins; ++i)
    for (int o = i + 1; o < kBins && M.absorptance(i) > 0; ++o)
      share = std::max(share, M(i, o) / M.absorptance(i));
  ASSERT_LT(secondOrderBound * share, 3e-3 * L[static_cast<size_t>(ReradiationMatrix::binOf(552))])
      << secondOrderBound << " " << share;
  EXPECT_GT(L[static_cast<size_t>(ReradiationMatrix::binOf(552))], 0.05);

  RenderOptions options;
  options.bands = Sensor(SpectralBands::parse("540:600:10"));
  const RenderOutput out = renderText(
      sceneText(
          "<xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>3</depth><sampl>4096</"
          "sampl>"
          "<background>300:1, 419.99:1, 420:0, 1100:0</background>",
          kCentreCamera,
          "<sphere><center>0,0,0</center><radius>1</radius><material>interface</material><medium>"
          "<sigma_a>0</sigma_a><sigma_s>0</sigma_s><fluorescence><absorption>380</absorption>"
          "<stokes>170</stokes><width>5</width><skew>0</skew><yield>0.5</yield><peak>4</peak>"
          "</fluorescence></medium></sphere>"),
      options);
  // Each 10 nm band is two bins.
  expectBands(
      out.film,
      [&](int b) {
        const int bin = ReradiationMatrix::binOf(out.film.bands().centroid(b) - 2.5);
        return (L[static_cast<size_t>(bin)] + L[static_cast<size_t>(bin) + 1]) / 2;
      },
      0.01);
}

} // namespace
} // namespace nx

namespace nx {
namespace {

std::string cube(const char* file, const std::string& material) {
  return std::string("<mesh file=\"") + NX_TEST_DATA_DIR + "/media/" + file + "\"><material>" +
         material + "</material><medium><sigma_a extrapolate=\"hold\">" + kSigmaA +
         "</sigma_a><sigma_s>0</sigma_s></medium></mesh>";
}

// Media in closed meshes: a cube [-1, 1]^3 of the absorber seen face-on reads exp(-2 sigma_a)
// whichever way its triangles are wound, exp(-sigma_a) from its centre; an open box is
// refused.
TEST(Media, BeerLambertThroughClosedMeshes) {
  for (const char* file : {"cube.obj", "cube_inward.obj"}) {
    const RenderOutput out =
        renderText(sceneText(kBackground, kFarCamera, cube(file, "interface")));
    expectBands(out.film, bandsOf(out.film, [](double s) { return std::exp(-2 * s); }), 0.01, {},
                file);
  }
  const RenderOutput inside =
      renderText(sceneText(kBackground,
                           "<position>0,0,0</position><look_at>0,0,1</look_at>"
                           "<fov>1</fov>",
                           cube("cube_inward.obj", "interface")));
  expectBands(inside.film, bandsOf(inside.film, [](double s) { return std::exp(-s); }), 0.01, {},
              "inside");
  const std::string error = test::errorMessage(
      [&] { renderText(sceneText(kBackground, kFarCamera, cube("open_box.obj", "interface"))); });
  EXPECT_NE(error.find("expected a closed mesh around a <medium> (every edge shared by two "
                       "triangles wound alike), found an edge used by one triangle only (a hole)"),
            std::string::npos)
      << error;
}

// Media the renderer cannot walk as asked are reported, not left to darken silently: paths cut
// at kMaxPathBounces are counted (a furnace of sigma_s 1e4 seen from its centre: almost every
// path; a thin one: none), and a mean free path near the float resolution of positions where
// the medium stands is a build warning (1e-4 at 1e4 from the origin; not 0.1 at the origin).
TEST(Media, DenseMediaAreReportedNotSilentlyDark) {
  const RenderOutput dense = renderText(sceneText(
      "<xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode><depth>2</depth><sampl>8</sampl>"
      "<background>1</background>",
      kCentreCamera,
      "<sphere><center>0,0,0</center><radius>1</radius><material>interface</material><medium>"
      "<sigma_a>0</sigma_a><sigma_s>1e4</sigma_s></medium></sphere>"));
  EXPECT_GT(dense.stats.bounceLimited, dense.stats.samples * 9 / 10);
  ASSERT_FALSE(warningsOf(dense.stats).empty());
  EXPECT_NE(warningsOf(dense.stats).front().find("reached the limit of 1024 bounces"),
            std::string::npos);
  const RenderOutput thin = renderText(sceneText(
      "<xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode><depth>2</depth><sampl>8</sampl>"
      "<background>1</background>",
      kCentreCamera,
      "<sphere><center>0,0,0</center><radius>1</radius><material>interface</material><medium>"
      "<sigma_a>0</sigma_a><sigma_s>0.5</sigma_s></medium></sphere>"));
  EXPECT_EQ(thin.stats.bounceLimited, 0u);
  EXPECT_TRUE(warningsOf(thin.stats).empty());
  const auto buildWarnings = [](const std::string& centre, const std::string& sigmaS) {
    const std::string body = "<sphere><center>" + centre +
                             "</center><radius>1</radius><material>interface</material>"
                             "<medium><sigma_a>0</sigma_a><sigma_s>" +
                             sigmaS + "</sigma_s></medium></sphere>";
    return resolveRenderScene(parseScene(sceneText(kBackground, kFarCamera, body), "t.scn"))
        .warnings;
  };
  const std::vector<std::string> far = buildWarnings("1e4,0,0", "1e4");
  ASSERT_EQ(far.size(), 1u);
  EXPECT_EQ(far[0].rfind("t.scn:", 0), 0u) << far[0];
  EXPECT_NE(far[0].find("warning: the medium's shortest mean free path (0.0001 units) is within "
                        "50 steps of the float resolution"),
            std::string::npos)
      << far[0];
  EXPECT_TRUE(buildWarnings("0,0,0", "10").empty());
  EXPECT_EQ(buildWarnings("0,0,0", "1e6").size(), 1u); // 1e-6 against steps of 1.2e-7
}

} // namespace
} // namespace nx
