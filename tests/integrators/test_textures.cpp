// Reflectance textures: lookups against known texels, the ColorChecker chart, a spectral EXR on
// a quad, an sRGB PNG upsampled per texel, and the errors of malformed textures.

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "io/spectral_exr.h"
#include "spectra/colorchecker.h"
#include "spectra/colour.h"
#include "spectra/rgb_upsampling.h"
#include "support/errors.h"
#include "support/flat_wavelengths.h"
#include "support/statistics.h"

namespace nx {
namespace {

float fl(int i) {
  return static_cast<float>(i);
}

// A 2 x 2 texture with bands at 500, 600, 700 nm: texel (x, y) band b holds
// 0.1 (1 + x + 2 y) + 0.01 b.
std::shared_ptr<const ReflectanceTexture> smallTexture(bool holdEnds = false) {
  std::vector<float> v;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)
      for (int b = 0; b < 3; ++b)
        v.push_back(0.1f * static_cast<float>(1 + x + 2 * y) + 0.01f * static_cast<float>(b));
  return ReflectanceTexture::spectralImage(2, 2, {500, 600, 700}, v, holdEnds);
}

TEST(Textures, ImageLookupsMatchKnownTexels) {
  const auto t = smallTexture();
  // Texel centres: (u, v) = ((x + 1/2) / 2, 1 - (y + 1/2) / 2); row 0 is the top.
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) / 2,
                  v = 1 - (static_cast<float>(y) + 0.5f) / 2;
      EXPECT_NEAR(t->evaluate(u, v, test::flatWavelengths(600))[0],
                  0.1f * fl(1 + x + 2 * y) + 0.01f, 1e-6f);
    }
  // Bilinear: the centre of the image is the mean of the four texels.
  EXPECT_NEAR(t->evaluate(0.5f, 0.5f, test::flatWavelengths(500))[0], 0.25f, 1e-6f);
  // A quarter of the way from texel (0,0) to texel (1,0).
  EXPECT_NEAR(t->evaluate(0.375f, 0.75f, test::flatWavelengths(500))[0], 0.125f, 1e-6f);
  // Linear between band centroids (the last one included); beyond the ends 0, or the ends held
  // when asked (extrapolate="hold").
  EXPECT_NEAR(t->evaluate(0.25f, 0.75f, test::flatWavelengths(550))[0], 0.105f, 1e-6f);
  EXPECT_NEAR(t->evaluate(0.25f, 0.75f, test::flatWavelengths(700))[0], 0.12f, 1e-6f);
  EXPECT_EQ(t->evaluate(0.25f, 0.75f, test::flatWavelengths(420))[0], 0.0f);
  EXPECT_EQ(t->evaluate(0.25f, 0.75f, test::flatWavelengths(900))[0], 0.0f);
  const auto held = smallTexture(true);
  EXPECT_NEAR(held->evaluate(0.25f, 0.75f, test::flatWavelengths(420))[0], 0.1f, 1e-6f);
  EXPECT_NEAR(held->evaluate(0.25f, 0.75f, test::flatWavelengths(900))[0], 0.12f, 1e-6f);
  ASSERT_TRUE(t->dataRangeNm().has_value());
  EXPECT_EQ(*t->dataRangeNm(), std::make_pair(500.0, 700.0));
  // Outside [0, 1] the edge texels continue.
  EXPECT_NEAR(t->evaluate(-3.0f, 7.0f, test::flatWavelengths(500))[0], 0.1f, 1e-6f);
}

TEST(Textures, ChartPatchesAndFrame) {
  const auto chart = ReflectanceTexture::colorChecker();
  for (int row = 0; row < kColorCheckerRows; ++row)
    for (int col = 0; col < kColorCheckerColumns; ++col) {
      const float u = (fl(col) + 0.5f) / kColorCheckerColumns,
                  v = 1 - (fl(row) + 0.5f) / kColorCheckerRows;
      for (float nm : {450.0f, 550.0f, 650.0f})
        EXPECT_FLOAT_EQ(chart->evaluate(u, v, test::flatWavelengths(nm))[0],
                        static_cast<float>(colorCheckerPatch(row * kColorCheckerColumns + col)(nm)))
            << row << "," << col;
      // The frame between patches.
      const float edgeU = fl(col) / kColorCheckerColumns + 0.01f;
      EXPECT_FLOAT_EQ(chart->evaluate(edgeU, v, test::flatWavelengths(550))[0], kColorCheckerFrame);
    }
}

std::string sceneWith(const std::string& reflectance) {
  // A 0.6 x 0.4 quad facing the camera under a uniform background of radiance 1, nothing else:
  // its radiance is its reflectance (it sees the background over its whole hemisphere).
  // Depth 2: Russian roulette from the second vertex on. (At depth 1 the roulette at the quad
  // kept the BSDF-sampled half of its direct light with probability rho: a black patch read
  // 0.006 in most pixels and 0.23 in one of eight, unbiased but a weak test.)
  return "<scene><settings><xres>60</xres><yres>40</yres><mode>spectral_mcpt</mode><sampl>16"
         "</sampl><depth>2</depth><background>1</background></settings><camera><position>0,0,-1"
         "</position><look_at>0,0,0</look_at><fov>33.4</fov></camera>"
         "<quad><origin>-0.3,-0.2,0</origin><edge_u>0.6,0,0</edge_u><edge_v>0,0.4,0</edge_v>"
         "<material>matte</material>" +
         reflectance + "</quad></scene>";
}

// The chart on a quad: the pixels at a patch's centre read the patch's reflectance, band by
// band (the band average of the measured spectrum).
TEST(Textures, ChartOnAQuadRendersEachPatch) {
  const RenderScene scene =
      buildRenderScene(parseScene(sceneWith("<reflectance texture=\"colorchecker\"/>"), "t.scn"));
  RenderOptions o;
  const RenderOutput out = render(scene, o);
  // The quad spans the image (fov chosen so), so the pixel of (u, v) is (60 u, 40 (1 - v)).
  for (int patch : {0, 6, 14, 18, 23}) {
    const int row = patch / kColorCheckerColumns, col = patch % kColorCheckerColumns;
    const int px = col * 10 + 5, py = row * 10 + 5;
    for (int b = 0; b < out.film.bands().count(); b += 6) {
      test::RunningStats s;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) s.add(out.film.bandMean(px + dx, py + dy, b));
      const double expected = bandAverage(colorCheckerPatch(patch), out.film.bands(), b);
      EXPECT_NEAR(s.mean, expected, 5 * s.standardError() + 0.01 * expected)
          << colorCheckerPatchNames()[static_cast<size_t>(patch)] << " band " << b;
    }
  }
}

// The chart's data covers 380-780 nm: a render tracing beyond warns (naming the texture and
// its line), extrapolate="hold" holds each patch's 780 nm value and does not warn, "zero" is 0
// without a warning; the texture form took no extrapolate="..." before.
TEST(Textures, ChartBeyondItsMeasuredRangeWarnsHoldsOrIsZero) {
  for (const char* mode : {"", "hold", "zero"}) {
    SCOPED_TRACE(mode);
    const std::string attr = *mode ? std::string(" extrapolate=\"") + mode + "\"" : "";
    const RenderScene scene = buildRenderScene(
        parseScene(sceneWith("<reflectance texture=\"colorchecker\"" + attr + "/>"), "t.scn"));
    const std::vector<std::string> w = extrapolationWarnings(scene, 600, 975);
    if (!*mode) {
      ASSERT_EQ(w.size(), 1u);
      EXPECT_NE(w[0].find("t.scn:"), std::string::npos) << w[0];
      EXPECT_NE(w[0].find("colorchecker"), std::string::npos) << w[0];
      EXPECT_NE(w[0].find("380-780"), std::string::npos) << w[0];
    } else {
      EXPECT_TRUE(w.empty()) << w[0];
    }
    EXPECT_TRUE(extrapolationWarnings(scene, 400, 700).empty());
    const Material& m = scene.materials[scene.meshes[0].whole.material];
    ASSERT_TRUE(m.texture);
    // dark_skin's cell centre (top left) at 900 nm and at 780 nm.
    const float at900 = m.texture->evaluate(1 / 12.0f, 1 - 1 / 8.0f, test::flatWavelengths(900))[0];
    const float at780 = m.texture->evaluate(1 / 12.0f, 1 - 1 / 8.0f, test::flatWavelengths(780))[0];
    EXPECT_GT(at780, 0.3f);
    EXPECT_EQ(at900, std::string(mode) == "hold" ? at780 : 0.0f);
  }
  EXPECT_NE(test::errorMessage([] {
              parseScene(sceneWith("<reflectance texture=\"colorchecker\" extrapolate=\"clamp\"/>"),
                         "t.scn");
            }).find("expected extrapolate=\"zero\" or extrapolate=\"hold\""),
            std::string::npos);
}

// A spectral EXR in this project's layout is read as a texture: its texels come back at their
// uv; reflectances outside [0, 1] are refused with the pixel and band named.
TEST(Textures, SpectralExrTextureIsReadAndChecked) {
  SpectralImage img;
  img.width = 3;
  img.height = 2;
  img.bands = Sensor(SpectralBands::parse("450:650:100"));
  for (int p = 0; p < 6; ++p) {
    for (int b = 0; b < 3; ++b)
      img.radiance.push_back(0.1f * static_cast<float>(p) + 0.02f * fl(b));
    for (int c = 0; c < 3; ++c) img.rgb.push_back(0.5f);
  }
  img.attributes["nxrender.bands"] = img.bands.toString();
  const std::string path = ::testing::TempDir() + "/chart_texture.exr";
  writeSpectralExr(path, img);
  const RenderScene scene = buildRenderScene(parseScene(
      sceneWith("<reflectance texture=\"chart_texture.exr\"/>"), ::testing::TempDir() + "/t.scn"));
  const auto& tex = scene.materials[scene.meshes[0].whole.material].texture;
  ASSERT_TRUE(tex);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      for (int b = 0; b < 3; ++b) {
        const float u = (fl(x) + 0.5f) / 3, v = 1 - (fl(y) + 0.5f) / 2;
        EXPECT_NEAR(tex->evaluate(u, v, test::flatWavelengths(450.0f + 100.0f * fl(b)))[0],
                    0.1f * fl(y * 3 + x) + 0.02f * fl(b), 1e-6f);
      }
  img.radiance[4 * 3 + 1] = 1.5f; // pixel (1, 1), band 550 nm
  writeSpectralExr(path, img);
  const std::string message = test::errorMessage([&] {
    buildRenderScene(parseScene(sceneWith("<reflectance texture=\"chart_texture.exr\"/>"),
                                ::testing::TempDir() + "/t.scn"));
  });
  EXPECT_NE(message.find("expected reflectances within [0, 1], found 1.5 at pixel 1,1 in band "
                         "550 nm"),
            std::string::npos)
      << message;
}

// An sRGB PNG is upsampled per texel through the table: at a texel's centre the texture is
// the upsampled spectrum of that texel's colour, between texels the bilinear mix of spectra.
TEST(Textures, SrgbPngTexelsAreUpsampledSpectra) {
  const std::vector<unsigned char> px = {230, 40, 30, 20, 180, 60, 40, 60, 200, 128, 128, 128};
  const std::string path = ::testing::TempDir() + "/rgb_texture.png";
  ASSERT_TRUE(stbi_write_png(path.c_str(), 2, 2, 3, px.data(), 6));
  const RenderScene scene = buildRenderScene(parseScene(
      sceneWith("<reflectance texture=\"rgb_texture.png\"/>"), ::testing::TempDir() + "/t.scn"));
  const auto& tex = scene.materials[scene.meshes[0].whole.material].texture;
  ASSERT_TRUE(tex);
  std::vector<Spectrum> expected;
  for (int t = 0; t < 4; ++t) {
    const unsigned char* c = &px[static_cast<size_t>(t * 3)];
    expected.push_back(upsampleSrgbReflectance(
        {srgbDecode(c[0] / 255.0), srgbDecode(c[1] / 255.0), srgbDecode(c[2] / 255.0)}));
  }
  for (float nm : {400.0f, 480.0f, 550.0f, 610.0f, 700.0f}) {
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) {
        const float u = (fl(x) + 0.5f) / 2, v = 1 - (fl(y) + 0.5f) / 2;
        EXPECT_NEAR(tex->evaluate(u, v, test::flatWavelengths(nm))[0],
                    expected[static_cast<size_t>(y * 2 + x)](nm), 1e-5)
            << nm << " nm, texel " << x << "," << y;
      }
    double mean = 0;
    for (const Spectrum& e : expected) mean += e(nm) / 4;
    EXPECT_NEAR(tex->evaluate(0.5f, 0.5f, test::flatWavelengths(nm))[0], mean, 1e-5) << nm;
  }
  // The red texel reflects red: more at 650 nm than at 450 nm.
  EXPECT_GT(expected[0](650), 3 * expected[0](450));
}

} // namespace
} // namespace nx
