// The spectral environment light: its importance sampling against its own pdf (the density
// integrates to one, a sample's pdf is the density at its direction, texels are drawn as often
// as their weight says: chi-square), a constant map against the uniform background, and a
// map with one bright texel against the closed form of the floor it lights:
//   L = rho / pi * Lt * integral over the texel of cos(theta) d(omega)
//     = rho / pi * Lt * (2 pi / W) * (sin^2 theta_b - sin^2 theta_a) / 2
// for a floor whose normal is the map's zenith (+y), theta_a..theta_b the texel's row.

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>
#include <limits>

#include <cmath>
#include <functional>
#include <string>

#include "integrators/render_scene.h"
#include "integrators/sampling.h"
#include "integrators/scene_reader.h"
#include "io/spectral_exr.h"
#include "support/constant_map.h"
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

// The environment map `map` lighting a matte floor, resolved.
RenderScene environmentOverAFloor(const std::string& map) {
  return resolveRenderScene(parseScene(
      sceneWith("", kLookDown,
                "<light type=\"environment\"><file>" + map +
                    "</file></light>"
                    "<plane><normal>0,1,0</normal><distance>0</distance><material>matte</material>"
                    "<reflectance>0.5</reflectance></plane>"),
      "t.scn"));
}

// Lanes at 450, 480, ... nm.
SampledWavelengths visibleLanes() {
  SampledWavelengths lambda;
  for (int i = 0; i < kLanes; ++i) lambda.lambda[i] = 450.0f + 30.0f * static_cast<float>(i);
  return lambda;
}

TEST(EnvironmentLight, SamplingFollowsItsPdf) {
  const int w = 8, h = 4;
  const std::string map = writeMap("env_sampling.exr", w, h, [](int x, int y, int b) {
    return 0.1f + static_cast<float>((x * 7 + y * 3) % 5) + 0.1f * static_cast<float>(b);
  });
  const RenderScene scene = environmentOverAFloor(map);
  const EnvironmentLight& env = std::get<EnvironmentLight>(scene.lights[0]);
  const SampledWavelengths lambda = visibleLanes();
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
// A direction with NaN or infinite components (a path gone numerically wrong) falls in one of
// the map's texels, never outside them: texelOf once clamped its row on one side only.
TEST(EnvironmentLight, NonFiniteDirectionsStayInsideTheMap) {
  const int w = 8, h = 4;
  const std::string map = writeMap("env_nan.exr", w, h, [](int, int, int) { return 1.0f; });
  const RenderScene scene = environmentOverAFloor(map);
  const EnvironmentLight& env = std::get<EnvironmentLight>(scene.lights[0]);
  const SampledWavelengths lambda = visibleLanes();
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = INFINITY;
  for (const Vec3& d : {Vec3(nan, nan, nan), Vec3(nan, 1, 0), Vec3(0, nan, 0), Vec3(0, -1, nan),
                        Vec3(inf, 0, 0), Vec3(0, -inf, 0), Vec3(-inf, inf, -inf), Vec3(0, 0, 0)}) {
    EXPECT_LT(env.texelOf(d), static_cast<size_t>(w * h)) << d.x << " " << d.y << " " << d.z;
    (void)env.radiance(d, lambda);
    (void)env.pdf(d);
  }
}

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
  const std::string map = test::writeConstantMap("env_narrow.exr", 4, 2, "500:600:50", 1.0f);
  const RenderScene scene = resolveRenderScene(parseScene(
      sceneWith("", kLookDown, "<light type=\"environment\"><file>" + map + "</file></light>"),
      "t.scn"));
  const std::vector<std::string> w = extrapolationWarnings(scene, 400, 700);
  ASSERT_EQ(w.size(), 1u);
  // Its bands cover 475-625 nm (each 50 nm wide); the advice is what the light takes.
  EXPECT_NE(w[0].find("t.scn:1: warning: spectrum '" + map + "' is tabulated over 475-625 nm"),
            std::string::npos)
      << w[0];
  EXPECT_NE(w[0].find("(write <extrapolate>zero</extrapolate> or <extrapolate>hold</extrapolate> "
                      "in the <light> to choose)"),
            std::string::npos)
      << w[0];
  EXPECT_TRUE(extrapolationWarnings(scene, 480, 620).empty());
  // Taking the advice: no warning. Seen directly (1 per band where the map covers), hold
  // renders the edge bands' radiance beyond; zero renders nothing there, so a band of the
  // render (100 nm wide) gets the share of it within 475-625 nm.
  const std::string sky = "<position>0,0,0</position><look_at>0,0,1</look_at><fov>40</fov>";
  RenderOptions o;
  o.samples = 64;
  for (const std::string choice : {"hold", "zero"}) {
    const std::string text =
        sceneWith("", sky,
                  "<light type=\"environment\"><file>" + map + "</file><extrapolate>" + choice +
                      "</extrapolate></light>");
    EXPECT_TRUE(
        extrapolationWarnings(resolveRenderScene(parseScene(text, "t.scn")), 400, 700).empty())
        << choice;
    const Film f = renderText(text, o).film;
    for (int band = 0; band < f.bands().count(); ++band) {
      const double c = f.bands().centroid(band);
      const double want =
          choice == "hold" ? 1.0
                           : std::max(0.0, std::min(c + 50, 625.0) - std::max(c - 50, 475.0)) / 100;
      const test::RunningStats st = bandStats(f, band);
      if (want == 0) {
        EXPECT_EQ(st.mean, 0.0) << choice << " band " << c;
        continue;
      }
      EXPECT_LT(std::abs(st.mean - want), 5 * st.standardError() + 1e-6)
          << choice << " band " << c << ": " << st.mean << " expected " << want;
      EXPECT_LT(st.standardError(), 0.05 * want) << choice << " band " << c;
    }
  }
}

// A map written with the render's own bands covers each band's support: seen directly, its
// edge bands are its value (they were half: the map was 0 from their centroid out), and a
// sphere it lights matches the equal uniform background.
TEST(EnvironmentLight, EdgeBandsOfTheMapCoverTheirSupport) {
  const std::string map = test::writeConstantMap("env_own_bands.exr", 8, 4, "400:700:10", 0.7f);
  const std::string light = "<light type=\"environment\"><file>" + map + "</file></light>";
  auto scene = [&](const std::string& settings, const std::string& camera,
                   const std::string& body) {
    return sceneText("<xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode>"
                     "<bands>400:700:10</bands>" +
                         settings,
                     camera, body);
  };
  const std::string sky = "<position>0,0,0</position><look_at>0,0,1</look_at><fov>40</fov>";
  EXPECT_TRUE(extrapolationWarnings(resolveRenderScene(parseScene(scene("", sky, light), "t.scn")),
                                    395, 705)
                  .empty());
  RenderOptions o;
  o.samples = 64; // the lanes land on a band a few times per sample: noise of their count
  expectBands(
      renderText(scene("", sky, light), o).film, [](int) { return 0.7; }, 0.05);
  const std::string sphere = "<sphere><center>0,0,0</center><radius>1</radius><material>matte"
                             "</material><reflectance>0.5</reflectance></sphere>";
  const std::string camera = "<position>0,0,-2</position><look_at>0,0,0</look_at><fov>40</fov>";
  o.samples = 64;
  const Film a = renderText(scene("", camera, light + sphere), o).film;
  const Film b = renderText(scene("<background>0.7</background>", camera, sphere), o).film;
  for (int band : {0, 1, a.bands().count() - 2, a.bands().count() - 1}) {
    test::RunningStats d; // paired over pixels: the same pixel in both renders
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) d.add(a.bandMean(x, y, band) - b.bandMean(x, y, band));
    EXPECT_LT(std::abs(d.mean), 5 * d.standardError()) << "band " << a.bands().centroid(band);
    EXPECT_LT(d.standardError(), 0.05 * 0.35) << "band " << a.bands().centroid(band);
  }
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
  const std::string lit = writeMap("env_lit.exr", 4, 2, [](int, int, int) { return 1.0f; });
  EXPECT_EQ(error("<light type=\"environment\"><file>" + lit +
                  "</file><extrapolate>clamp</extrapolate></light>"),
            "t.scn:1: expected <extrapolate> zero or hold, found 'clamp'");
  // A reflective file (T.<wavelength> channels, Fichet et al. 2021) holds reflectances.
  const std::string reflective = ::testing::TempDir() + "/env_reflective.exr";
  {
    Imf::Header header(4, 2);
    std::vector<float> values(8, 0.5f);
    Imf::FrameBuffer fb;
    for (const char* c : {"T.450nm", "T.550nm"}) {
      header.channels().insert(c, Imf::Channel(Imf::FLOAT));
      fb.insert(c, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()), sizeof(float),
                              4 * sizeof(float)));
    }
    Imf::OutputFile file(reflective.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(2);
  }
  EXPECT_EQ(error("<light type=\"environment\"><file>" + reflective + "</file></light>"),
            "t.scn:1: " + reflective +
                ": expected an emissive spectral EXR (S0.<wavelength> channels: radiance), found "
                "a reflective one (T.<wavelength> channels: reflectances, for a <reflectance "
                "texture=\"...\">)");
}

} // namespace
} // namespace nx
