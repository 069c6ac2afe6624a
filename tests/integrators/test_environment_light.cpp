// The spectral environment light: its importance sampling against its own pdf (the density
// integrates to one, a sample's pdf is the density at its direction, texels are drawn as often
// as their weight says: chi-square), a constant map against the uniform background, and a
// map with one bright texel against the closed form of the floor it lights:
//   L = rho / pi * Lt * integral over the texel of cos(theta) d(omega)
//     = rho / pi * Lt * (2 pi / W) * (sin^2 theta_b - sin^2 theta_a) / 2
// for a floor whose normal is the map's zenith (+y), theta_a..theta_b the texel's row.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "integrators/render_scene.h"
#include "integrators/sampling.h"
#include "io/spectral_exr.h"
#include "support/errors.h"
#include "support/render_checks.h"
#include "support/statistics.h"

namespace nx {
namespace {

// Writes a W x H map in the project's layout with bands covering the traced range.
std::string writeMap(const std::string& name, int w, int h,
                     const std::function<float(int, int, int)>& value) {
  SpectralImage img;
  img.width = w;
  img.height = h;
  img.bands = Sensor(SpectralBands::parse("350:1050:100"));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      for (int b = 0; b < img.bands.count(); ++b) img.radiance.push_back(value(x, y, b));
      for (int c = 0; c < 3; ++c) img.rgb.push_back(0.5f);
    }
  img.attributes["nxrender.bands"] = img.bands.toString();
  const std::string path = ::testing::TempDir() + "/" + name;
  writeSpectralExr(path, img);
  return path;
}

std::string sceneWith(const std::string& settingsExtra, const std::string& camera,
                      const std::string& body) {
  return sceneText("<xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode>"
                   "<bands>400:700:100</bands>" +
                       settingsExtra,
                   camera, body);
}

const std::string kLookDown = "<position>0,5,0</position><look_at>0,0,0</look_at><up>0,0,1</up>"
                              "<fov>10</fov>";

TEST(EnvironmentLight, SamplingFollowsItsPdf) {
  const int w = 8, h = 4;
  const std::string map = writeMap("env_sampling.exr", w, h, [](int x, int y, int b) {
    return 0.1f + static_cast<float>((x * 7 + y * 3) % 5) + 0.1f * static_cast<float>(b);
  });
  const RenderScene scene = resolveRenderScene(parseScene(
      sceneWith("", kLookDown,
                "<light type=\"environment\"><file>" + map +
                    "</file></light>"
                    "<plane><normal>0,1,0</normal><distance>0</distance><material>matte</material>"
                    "<reflectance>0.5</reflectance></plane>"),
      "t.scn"));
  const EnvironmentLight& env = std::get<EnvironmentLight>(scene.lights[0]);
  SampledWavelengths lambda;
  for (int i = 0; i < kLanes; ++i) lambda.lambda[i] = 450.0f + 30.0f * static_cast<float>(i);
  // Texel counts against the texels' probabilities (weight x sin theta, normalised).
  const int n = 200000;
  std::vector<double> counts(static_cast<size_t>(w * h), 0.0);
  for (int i = 0; i < n; ++i) {
    LightSample ls;
    const Sample2 u{sampleValue(SamplerKind::Independent, 1, static_cast<uint32_t>(i), 0, 7),
                    sampleValue(SamplerKind::Independent, 1, static_cast<uint32_t>(i), 1, 7)};
    ASSERT_TRUE(env.sample(Vec3(0, 0, 0), u, lambda, ls)) << u.u << ", " << u.v;
    ASSERT_NEAR(ls.pdf, env.pdf(ls.wi), 1e-3f * ls.pdf);
    ASSERT_TRUE(ls.infinite);
    counts[env.texelOf(ls.wi)] += 1;
  }
  double chi2 = 0;
  for (size_t t = 0; t < counts.size(); ++t) {
    const double expected = (*env.texelPdf)[t] / static_cast<double>(w * h) * n;
    chi2 += (counts[t] - expected) * (counts[t] - expected) / expected;
  }
  const double dof = w * h - 1;
  EXPECT_LT(chi2, dof + 5 * std::sqrt(2 * dof)) << "texels drawn unlike their probabilities";
  // The density integrates to one over the sphere (uniform directions, Monte Carlo).
  test::RunningStats integral;
  for (int i = 0; i < n; ++i) {
    const Vec3 d = sampleUniformSphere(
        {sampleValue(SamplerKind::Independent, 2, static_cast<uint32_t>(i), 0, 9),
         sampleValue(SamplerKind::Independent, 2, static_cast<uint32_t>(i), 1, 9)});
    integral.add(env.pdf(d) * 4 * kPi);
  }
  EXPECT_NEAR(integral.mean, 1.0, 5 * integral.standardError());
  EXPECT_LT(integral.standardError(), 0.01);
}

// A constant map is the uniform background, within noise (its own sampling differs).
TEST(EnvironmentLight, ConstantMapIsTheUniformBackground) {
  const float c = 0.7f;
  const std::string map = writeMap("env_constant.exr", 16, 8, [&](int, int, int) { return c; });
  const std::string sphere = "<sphere><center>0,0,0</center><radius>1</radius><material>matte"
                             "</material><reflectance>0.5</reflectance></sphere>";
  const std::string camera = "<position>0,0,-4</position><look_at>0,0,0</look_at><fov>40</fov>";
  RenderOptions o;
  o.samples = 64;
  const Film a =
      renderText(sceneWith("", camera,
                           "<light type=\"environment\"><file>" + map + "</file></light>" + sphere),
                 o)
          .film;
  const Film b = renderText(sceneWith("<background>0.7</background>", camera, sphere), o).film;
  for (int band = 0; band < a.bands().count(); ++band) {
    const test::RunningStats sa = bandStats(a, band), sb = bandStats(b, band);
    EXPECT_NEAR(sa.mean, sb.mean,
                5 * std::sqrt(sa.standardError() * sa.standardError() +
                              sb.standardError() * sb.standardError()))
        << "band " << a.bands().centroid(band);
    EXPECT_GT(sa.mean, 0.3);
  }
}

// One bright texel lights a floor as the closed form says (a small distant source).
TEST(EnvironmentLight, OneBrightTexelIsADistantLightsClosedForm) {
  const int w = 32, h = 16, i0 = 5, j0 = 4;
  const float lt = 100;
  const double rho = 0.5;
  const std::string map = writeMap(
      "env_texel.exr", w, h, [&](int x, int y, int) { return x == i0 && y == j0 ? lt : 0.0f; });
  RenderOptions o;
  o.samples = 64;
  const Film film =
      renderText(sceneWith("<depth>1</depth>", kLookDown,
                           "<light type=\"environment\"><file>" + map +
                               "</file></light>"
                               "<plane><normal>0,1,0</normal><distance>0</distance><material>matte"
                               "</material><reflectance>" +
                               std::to_string(rho) + "</reflectance></plane>"),
                 o)
          .film;
  const double ta = kPi * j0 / h, tb = kPi * (j0 + 1) / h;
  const double expected = rho / kPi * lt * (2 * kPi / w) *
                          (std::sin(tb) * std::sin(tb) - std::sin(ta) * std::sin(ta)) / 2;
  expectBands(
      film, [&](int) { return expected; }, 0.02);
}

// A map whose bands end inside the traced range is 0 beyond them, and a render tracing there
// says so (the extrapolation warning names the map and its range).
TEST(EnvironmentLight, BandsEndingInsideTheTracedRangeWarn) {
  SpectralImage img;
  img.width = 4, img.height = 2;
  img.bands = Sensor(SpectralBands::parse("500:600:50"));
  img.radiance.assign(static_cast<size_t>(8 * img.bands.count()), 1.0f);
  img.rgb.assign(24, 0.5f);
  img.attributes["nxrender.bands"] = img.bands.toString();
  const std::string map = ::testing::TempDir() + "/env_narrow.exr";
  writeSpectralExr(map, img);
  const RenderScene scene = resolveRenderScene(parseScene(
      sceneWith("", kLookDown, "<light type=\"environment\"><file>" + map + "</file></light>"),
      "t.scn"));
  const std::vector<std::string> w = extrapolationWarnings(scene, 400, 700);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("t.scn:1: warning: spectrum '" + map + "' is tabulated over 500-600 nm"),
            std::string::npos)
      << w[0];
  EXPECT_TRUE(extrapolationWarnings(scene, 520, 580).empty());
}

TEST(EnvironmentLight, SceneErrors) {
  auto error = [](const std::string& light) {
    return test::errorMessage(
        [&] { (void)resolveRenderScene(parseScene(sceneWith("", kLookDown, light), "t.scn")); });
  };
  const std::string black = writeMap("env_black.exr", 4, 2, [](int, int, int) { return 0.0f; });
  EXPECT_NE(error("<light type=\"environment\"><file>" + black + "</file></light>")
                .find("expected an environment map that emits somewhere"),
            std::string::npos);
  const std::string negative =
      writeMap("env_negative.exr", 4, 2, [](int x, int, int) { return x == 1 ? -1.0f : 1.0f; });
  EXPECT_NE(
      error("<light type=\"environment\"><file>" + negative + "</file></light>")
          .find("expected radiance within [0, 1e+12] (after its scale), found -1 at texel 1,0"),
      std::string::npos);
  EXPECT_NE(error("<light type=\"environment\"><file>/nonexistent/sky.exr</file></light>")
                .find("t.scn:1: /nonexistent/sky.exr: cannot open"),
            std::string::npos);
  EXPECT_NE(error("<light type=\"environment\"></light>").find("expected <file> inside <light>"),
            std::string::npos);
}

} // namespace
} // namespace nx
