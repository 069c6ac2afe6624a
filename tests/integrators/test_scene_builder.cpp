#include <gtest/gtest.h>

#include <fstream>

#include "core/error.h"
#include "integrators/render_scene.h"
#include "integrators/scene_reader.h"
#include "spectra/colour.h"
#include "spectra/illuminants.h"
#include "spectra/rgb_upsampling.h"
#include "support/errors.h"

namespace nx {
namespace {

std::string scene(const std::string& body, const std::string& mode = "spectral_mcpt") {
  return "<scene>\n<settings><xres>8</xres><yres>6</yres><mode>" + mode +
         "</mode></settings>\n"
         "<camera><position>0, 0, -5</position><look_at>0, 0, 0</look_at></camera>\n" +
         body + "</scene>\n";
}

RenderScene build(const std::string& text) {
  return buildRenderScene(parseScene(text, "t.scn"));
}

std::string errorOf(const std::string& text) {
  return test::errorMessage([&] { build(text); });
}

TEST(SceneBuilder, EveryExampleSceneBuilds) {
  for (const char* name : {"thesis", "materials", "dispersion", "rgb_mcpt", "rt_whitted",
                           "extensions", "blacklight", "measured", "glass", "white_floor",
                           "snapshot16", "linescan204", "lab_bench", "tonic_water"}) {
    const std::string path = std::string(NX_SOURCE_DIR "/scenes/") + name + ".scn";
    EXPECT_NO_THROW(buildRenderScene(loadScene(path))) << path;
  }
}

TEST(SceneBuilder, ThesisScene) {
  const RenderScene s = buildRenderScene(loadScene(NX_SOURCE_DIR "/scenes/thesis.scn"));
  EXPECT_EQ(s.geometry->spheres().size(), 4u);
  EXPECT_EQ(s.geometry->planes().size(), 2u);
  ASSERT_EQ(s.materials.size(), 6u);
  EXPECT_EQ(s.materials[2].kind, MaterialKind::Dielectric);
  EXPECT_DOUBLE_EQ(s.materials[2].ior.at(550), 2.418);
  EXPECT_FALSE(s.materials[2].ior.dispersive());
  EXPECT_FLOAT_EQ(s.materials[3].roughness, 0.3f);        // metal
  EXPECT_DOUBLE_EQ(s.materials[0].reflectance(500), 0.5); // gray
  ASSERT_TRUE(s.materials[3].fluorescenceModel.has_value());
  EXPECT_EQ(s.materials[3].fluorescenceModel->absorptionPeakNm, 460);
  EXPECT_EQ(s.materials[3].fluorescenceModel->stokesNm, 220);
  EXPECT_EQ(s.materials[3].fluorescenceModel->widthNm, 20);
  EXPECT_EQ(s.materials[3].fluorescenceModel->skew, 10);
  EXPECT_EQ(s.materials[3].fluorescenceModel->quantumYield, 1);
  EXPECT_EQ(s.materials[3].fluorescenceModel->peakAbsorptance, 1);
  ASSERT_TRUE(s.materials[3].reradiation);
  // The absorption curve peaks at a_max = 1, left of its location (negative skew).
  int peak = 0;
  for (int i = 0; i < ReradiationMatrix::kBins; ++i)
    if (s.materials[3].reradiation->absorptance(i) > s.materials[3].reradiation->absorptance(peak))
      peak = i;
  EXPECT_DOUBLE_EQ(s.materials[3].reradiation->absorptance(peak), 1.0);
  EXPECT_LT(ReradiationMatrix::centre(peak), 460);
  EXPECT_TRUE(s.hasFluorescence);
  ASSERT_EQ(s.emission.size(), 1u);
  EXPECT_EQ(s.shapes(ShapeKind::Sphere)[3].emission, 0);
  EXPECT_NEAR(relativeLuminance(s.emission[0]), 1.0,
              1e-6);                                      // bbd65 is as bright as 1 (a float table)
  EXPECT_DOUBLE_EQ(s.materials[5].reflectance(550), 0.0); // an emitter without reflectance is black
  EXPECT_EQ(s.shapes(ShapeKind::Plane)[0].emission, -1);
}

TEST(SceneBuilder, ExtensionsResolve) {
  const RenderScene s = buildRenderScene(loadScene(NX_SOURCE_DIR "/scenes/extensions.scn"));
  EXPECT_NEAR(s.materials[1].reflectance(460), 0.1 + (0.6 - 0.1) * 10 / 70, 1e-12); // named pairs
  EXPECT_FLOAT_EQ(s.materials[1].roughness, 0.5f);
  EXPECT_EQ(s.materials[2].ior.kind, IorModel::Kind::Cauchy);
  EXPECT_NEAR(s.materials[2].ior.at(500), 1.5046 + 0.0042 / 0.25, 1e-12);
  EXPECT_NEAR(s.materials[3].reflectance(500), 0.60, 1e-12); // CSV file
  EXPECT_NEAR(s.emission[0](450), 6 * 0.60, 1e-12); // scene spectra are used as written, x scale
  ASSERT_TRUE(s.background.has_value());
  EXPECT_DOUBLE_EQ((*s.background)(600), 0.05);
  EXPECT_EQ(s.settings.bands.count(), 14);
}

TEST(SceneBuilder, DispersiveGlasses) {
  const RenderScene s = buildRenderScene(loadScene(NX_SOURCE_DIR "/scenes/dispersion.scn"));
  EXPECT_TRUE(s.materials[1].ior.dispersive());
  EXPECT_NEAR(s.materials[1].ior.at(589.3), 2.417, 2e-3);  // diamond n_D
  EXPECT_NEAR(s.materials[2].ior.at(587.6), 1.5168, 1e-4); // N-BK7 n_d
  EXPECT_GT(s.materials[2].ior.at(400), s.materials[2].ior.at(700));
  IorModel silica;
  ASSERT_TRUE(namedGlass("fused_silica", silica));
  EXPECT_NEAR(silica.at(587.6), 1.4585, 1e-4);
}

// The build step does not trust the loader's check of glass names: an unknown name in a
// scene description made otherwise (a tool, later the Python module) is an error, not n = 1.5.
TEST(SceneBuilder, UnknownGlassNameIsAnError) {
  SceneDesc d = parseScene(scene("<sphere><center>0,0,0</center><radius>1</radius><material>glass"
                                 "</material><ior>bk7</ior></sphere>\n"),
                           "t.scn");
  d.objects[0].params.getMutable<IorDesc>("ior")->name = "crown";
  EXPECT_EQ(test::errorMessage([&] { buildRenderScene(d); }),
            "t.scn:4: expected a named glass bk7, diamond or fused_silica, found 'crown'");
}

TEST(SceneBuilder, RgbModesUpsampleColours) {
  const RenderScene s = buildRenderScene(loadScene(NX_SOURCE_DIR "/scenes/rgb_mcpt.scn"));
  const Rgb red = reflectanceToLinearSrgb(s.materials[2].reflectance);
  EXPECT_NEAR(red.r, 0.9, 2e-3);
  EXPECT_NEAR(red.g, 0.1, 2e-3);
  EXPECT_NEAR(red.b, 0.1, 2e-3);
  // The light: colour (1, 0.9, 0.7) x 8, shown as that colour.
  const Rgb light = xyzToLinearSrgb(spectrumToXyz(s.emission[0]));
  EXPECT_NEAR(light.r, 8.0, 0.03);
  EXPECT_NEAR(light.g, 7.2, 0.03);
  EXPECT_NEAR(light.b, 5.6, 0.03);
  const RenderScene rt = buildRenderScene(loadScene(NX_SOURCE_DIR "/scenes/rt_whitted.scn"));
  ASSERT_EQ(rt.lights.size(), 2u);
  EXPECT_NEAR(xyzToLinearSrgb(spectrumToXyz(std::get<PointLight>(rt.lights[0]).intensity)).g, 40.0,
              0.1);
}

// Each mode prefers its own reflectance tag and falls back on the other.
TEST(SceneBuilder, ModesFallBackOnTheOtherReflectanceTag) {
  const std::string both =
      "<sphere><center>0,0,0</center><radius>1</radius><material>matte</material>"
      "<color>0.9, 0.1, 0.1, 1</color><reflectance>0.25</reflectance></sphere>\n";
  EXPECT_DOUBLE_EQ(build(scene(both)).materials[0].reflectance(500), 0.25);
  EXPECT_GT(build(scene(both, "mcpt")).materials[0].reflectance(650), 0.5);
  const std::string onlySpectrum =
      "<sphere><center>0,0,0</center><radius>1</radius><material>matte</material>"
      "<reflectance>0.25</reflectance><emission>D65</emission></sphere>\n";
  const RenderScene rt = build(scene(onlySpectrum, "rt"));
  EXPECT_DOUBLE_EQ(rt.materials[0].reflectance(500), 0.25);
  EXPECT_NEAR(relativeLuminance(rt.emission[0]), 1.0, 1e-9);
  for (const char* mode : {"rt", "mcpt", "spectral_mcpt"}) {
    SceneDesc d = loadScene(NX_SOURCE_DIR "/scenes/thesis.scn");
    d.settings.mode = std::string(mode) == "rt"     ? RenderMode::Rt
                      : std::string(mode) == "mcpt" ? RenderMode::Mcpt
                                                    : RenderMode::SpectralMcpt;
    EXPECT_NO_THROW(buildRenderScene(d)) << mode;
  }
}

TEST(SceneBuilder, ErrorsNameTheLine) {
  const std::string sphere = "<sphere><center>0,0,0</center><radius>1</radius>";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {scene(sphere + "<material>matte</material><reflectance>teal</reflectance></sphere>\n"),
       "t.scn:4: expected a reflectance name (red, orange, yellow, green, blue, purple, uv, gray, "
       "const, null, colorchecker:<patch> (dark_skin, ..., black_2), or a "
       "<spectrum> of the scene), found 'teal'"},
      {scene(sphere + "<material>matte</material><emission>D66x</emission></sphere>\n"),
       "t.scn:4: expected an illuminant name (A, D50"},
      {scene(sphere + "<material>matte</material><reflectance csv=\"missing.csv\"/></sphere>\n"),
       "t.scn:4: missing.csv: cannot open the table file"},
      {scene(sphere + "<material>matte</material><reflectance>1.5</reflectance></sphere>\n"),
       "t.scn:4: expected a reflectance within [0, 1] at every wavelength of 300-1100 nm, found "
       "1.5 "
       "at 300 nm"},
      {scene(sphere + "<material>glass</material><roughness>0.2</roughness></sphere>\n"),
       "t.scn:4: expected only <color>, <reflectance>, <ior>, <alpha>, <alpha_u>, <alpha_v> or "
       "<coating> on glass, found <roughness> (a dielectric's roughness is <alpha>)"},
      {scene(sphere +
             "<material>matte</material><reflectance>gray</reflectance><ior>1.3</ior></sphere>\n"),
       "t.scn:4: expected only <color>, <reflectance>, <roughness> or <fluorescence> on matte, "
       "found <ior>"},
      {scene(
           sphere +
           "<material>glass</material><fluorescence><absorption>uv</absorption><stokes>100</stokes>"
           "</fluorescence></sphere>\n"),
       "t.scn:4: expected only <color>, <reflectance>, <ior>, <alpha>, <alpha_u>, <alpha_v> or "
       "<coating> on glass, found <fluorescence> (fluorescent dielectrics need media"},
      {scene(sphere + "<material>matte</material></sphere>\n"),
       "t.scn:4: expected <reflectance> or <color> on a non-emitting matte object, found neither"},
      {scene(sphere + "<material>matte</material></sphere>\n", "mcpt"),
       "t.scn:4: expected <reflectance> or <color> on a non-emitting matte object, found neither"},
      {scene(sphere + "<material>glass</material><ior>cauchy: 0.5, 0.001</ior></sphere>\n"),
       "t.scn:4: expected an index of refraction within [1, 10] over 300-1100 nm, found 0.5008264 "
       "at "
       "1100 nm"},
      // Checked over the whole traced range (300-1100 nm), not only 360-830 nm.
      {scene(sphere + "<material>glass</material><ior>cauchy: 0.985, 0.012</ior></sphere>\n"),
       "t.scn:4: expected an index of refraction within [1, 10] over 300-1100 nm, found 0.9949174 "
       "at "
       "1100 nm"},
      // Exactly, not at whole nanometres: a Sellmeier pole at 500.5 nm.
      {scene(
           sphere +
           "<material>glass</material><ior>sellmeier: 1, 0, 0, 0.25050025, 0, 0</ior></sphere>\n"),
       "t.scn:4: expected an index of refraction within [1, 10] over 300-1100 nm, found"},
      {scene(sphere +
             "<material>matte</material><reflectance>400:0.5, 880:0.5, 900:1.3</reflectance>"
             "</sphere>\n"),
       "t.scn:4: expected a reflectance within [0, 1] at every wavelength of 300-1100 nm, found "
       "1.3 "
       "at 900 nm"},
      {scene(sphere +
             "<material>matte</material><reflectance>500:0.5, 500.4:1.5, 500.8:0.5</reflectance>"
             "</sphere>\n"),
       "t.scn:4: expected a reflectance within [0, 1] at every wavelength of 300-1100 nm, found "
       "1.5 "
       "at 500.4 nm"},
      {scene(sphere + "<material>matte</material><emission>400:1, 500:-0.5, 600:1</emission>"
                      "</sphere>\n"),
       "t.scn:4: expected an emission within [0, 1e+12] (W m^-2 sr^-1 nm^-1; W sr^-1 nm^-1 for "
       "point lights) at every wavelength of 300-1100 nm, found -0.5 at 500 nm"},
      // A white without visible light has no colour to balance the preview with (it wrote
      // previewWhite = -nan,1,-nan and a black preview).
      {"<scene>\n<settings><xres>8</xres><yres>6</yres><mode>spectral_mcpt</mode>"
       "<illum>0</illum></settings>\n<camera><position>0,0,-5</position><look_at>0,0,0</look_at>"
       "</camera>\n</scene>\n",
       "t.scn:2: expected an <illum> with visible light (the preview's white balance needs its "
       "colour), found luminance Y = 0"},
      {"<scene>\n<settings><xres>8</xres><yres>6</yres><mode>spectral_mcpt</mode>"
       "<illum>300:1, 350:1</illum></settings>\n<camera><position>0,0,-5</position>"
       "<look_at>0,0,0</look_at></camera>\n</scene>\n",
       "t.scn:2: expected an <illum> with visible light"},
      // Values that would overflow single precision (or its square in the error estimate)
      // are refused with the limit, whether given directly, through a scale or as a light.
      {scene(sphere + "<material>matte</material><emission>1e21</emission></sphere>\n"),
       "t.scn:4: expected an emission within [0, 1e+12] (W m^-2 sr^-1 nm^-1; W sr^-1 nm^-1 for "
       "point lights) at every wavelength of 300-1100 nm, found 1e+21 at 300 nm"},
      {scene(sphere + "<material>matte</material><emission scale=\"1e300\">D65</emission>"
                      "</sphere>\n"),
       "t.scn:4: expected an emission within [0, 1e+12]"},
      {scene(sphere + "<material>matte</material><emission>1e21</emission></sphere>\n", "rt"),
       "t.scn:4: expected an emission within [0, 1e+12]"},
      {scene("<light><position>0,5,0</position><color>1e13, 1e13, 1e13</color></light>\n"),
       "t.scn:4: expected an emission within [0, 1e+12]"},
      {scene(sphere +
             "<material>matte</material><reflectance>gray</reflectance><fluorescence>"
             "<absorption>teal</absorption><stokes>100</stokes></fluorescence></sphere>\n"),
       "t.scn:4: expected an absorption colour (red, orange, yellow, green, blue, purple, uv) or a "
       "wavelength in nm, found 'teal'"},
      {scene("<spectrum name=\"a\">b</spectrum>\n<spectrum name=\"b\">a</spectrum>\n" + sphere +
             "<material>matte</material><reflectance>a</reflectance></sphere>\n"),
       "expected spectrum definitions without a cycle, found one through"},
      {scene(sphere +
             "<material>matte</material><reflectance>400:0.5, 500:2</reflectance></sphere>\n"),
       "t.scn:4: expected a reflectance within [0, 1] at every wavelength of 300-1100 nm, found 2 "
       "at "
       "500 nm"},
  };
  for (const auto& [text, message] : cases) {
    const std::string got = errorOf(text);
    EXPECT_NE(got.find(message), std::string::npos)
        << "got:      " << got << "\nexpected: " << message;
  }
}

// The content digest (part of the render key of resume and merge) covers the bytes of every
// file the scene refers to, not only the scene text: a CSV edited between two farm parts
// changes it.
TEST(SceneBuilder, ContentDigestCoversReferencedFiles) {
  const std::string dir = ::testing::TempDir();
  const std::string text =
      scene("<sphere><center>0,0,0</center><radius>1</radius><material>matte</material>"
            "<reflectance csv=\"" +
            dir + "digest.csv\"/></sphere>\n");
  std::ofstream(dir + "digest.csv") << "400,0.5\n700,0.5\n";
  const uint64_t a = build(text).contentDigest, again = build(text).contentDigest;
  std::ofstream(dir + "digest.csv") << "400,0.5\n700,0.6\n";
  const uint64_t b = build(text).contentDigest;
  EXPECT_EQ(a, again);
  EXPECT_NE(a, b);
  // And the scene's state, not its spelling: a value changes it, white space does not.
  std::string other = text;
  other.replace(other.find("<radius>1<"), 10, "<radius>2<");
  EXPECT_NE(build(other).contentDigest, b);
  EXPECT_EQ(build(text + " ").contentDigest, b);
  std::string spaced = text;
  spaced.replace(spaced.find("<radius>1<"), 10, "<radius> 1.0 <");
  EXPECT_EQ(build(spaced).contentDigest, b);
}

// A point light's <emission> takes scale="..." like an object's.
TEST(SceneBuilder, PointLightEmissionScale) {
  const RenderScene s = build(scene(
      "<light><position>0,5,0</position><color>1,1,1</color><emission scale=\"50\">A</emission>"
      "</light>\n<sphere><center>0,0,0</center><radius>1</radius><material>matte</material>"
      "<reflectance>0.5</reflectance></sphere>\n"));
  const RenderScene one = build(
      scene("<light><position>0,5,0</position><color>1,1,1</color><emission>A</emission>"
            "</light>\n<sphere><center>0,0,0</center><radius>1</radius><material>matte</material>"
            "<reflectance>0.5</reflectance></sphere>\n"));
  EXPECT_NEAR(std::get<PointLight>(s.lights[0]).intensity(560),
              50 * std::get<PointLight>(one.lights[0]).intensity(560),
              1e-9 * std::get<PointLight>(s.lights[0]).intensity(560));
}

// A camera pasted from an OpenCV calibration: K, R, t and distortion as given (R made exactly
// orthonormal), the centre of projection at -R^T t; and the camera's errors, each at its line.
TEST(SceneBuilder, CalibratedCamera) {
  auto sceneWith = [](const std::string& camera) {
    return "<scene>\n<settings><xres>640</xres><yres>480</yres><mode>spectral_mcpt</mode>"
           "</settings>\n<camera>\n" +
           camera +
           "</camera>\n<sphere><center>0,0,0</center><radius>1</radius><material>matte"
           "</material><reflectance>0.5</reflectance></sphere>\n</scene>\n";
  };
  const std::string k = "<intrinsics>800, 790, 320.5, 240.25</intrinsics>\n";
  const std::string e = "<extrinsics>0, 0, -1, 0, 1, 0, 1, 0, 0, 0.5, 0, 4</extrinsics>\n";
  const RenderScene s = build(sceneWith(k + e + "<distortion>-0.1, 0.02, 0, 0</distortion>\n"));
  const CameraCalibration& c = s.camera.calibration();
  EXPECT_EQ(c.fx, 800);
  EXPECT_EQ(c.cy, 240.25);
  EXPECT_EQ(c.R[0][2], -1);
  EXPECT_EQ(c.t.z, 4);
  EXPECT_EQ(c.distortion[0], -0.1);
  // R maps world +x to camera z, so the camera looks along world +x from C = -R^T t.
  EXPECT_NEAR(s.camera.position().x, -4, 1e-12);
  EXPECT_NEAR(s.camera.position().z, 0.5, 1e-12);
  EXPECT_NEAR(s.camera.forward().x, 1, 1e-12);
  const std::vector<std::pair<std::string, std::string>> cases{
      {"<intrinsics>0, 800, 320, 240</intrinsics>\n<position>0,0,-5</position>"
       "<look_at>0,0,0</look_at>\n",
       "t.scn:4: expected focal lengths fx, fy > 0 in <intrinsics>, found '0, 800, 320, 240'"},
      {k + "<extrinsics>2, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 4</extrinsics>\n",
       "t.scn:5: expected a rotation R in <extrinsics> (R^T R = I within 1e-4, determinant +1), "
       "found R^T R off by 3, determinant 2"},
      {k + "<extrinsics>1, 0, 0, 0, 1, 0, 0, 0, -1, 0, 0, 4</extrinsics>\n",
       "t.scn:5: expected a rotation R in <extrinsics> (R^T R = I within 1e-4, determinant +1), "
       "found R^T R off by 0, determinant -1"},
      {k + e + "<position>0,0,-5</position>\n",
       "t.scn:6: expected either <extrinsics> or <position>/<look_at>/<up> in <camera>, found "
       "both (<position> and <extrinsics>)"},
      {k + e + "<fov>40</fov>\n",
       "t.scn:6: expected either <intrinsics> or <fov> in <camera>, found both"},
      {k + e + "<distortion>-1.5, 0, 0, 0</distortion>\n",
       "t.scn:6: expected a <distortion> that maps the image one to one, found a fold near pixel"},
      {k + e + "<thin_lens>0.1, 0</thin_lens>\n",
       "t.scn:6: expected an aperture radius >= 0 and a focus distance > 0 (scene units) in "
       "<thin_lens>, found '0.1, 0'"},
  };
  for (const auto& [camera, message] : cases) {
    const std::string got = errorOf(sceneWith(camera));
    EXPECT_EQ(got.substr(0, message.size()), message) << got;
  }
}

TEST(SceneBuilder, MeasuredMatrixCsv) {
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "m.csv") << "ex/em,400,500,600\n350,0.1,0.2,0.1\n450,0.05,0.3,0.2\n";
  std::ofstream(dir + "bad.csv") << "ex/em,400,500,600\n350,0.1,0.2\n";
  const std::string sphere =
      "<sphere><center>0,0,0</center><radius>1</radius><material>matte</material>"
      "<reflectance>gray</reflectance><fluorescence><matrix>";
  const RenderScene s = build(scene(sphere + dir + "m.csv</matrix></fluorescence></sphere>\n"));
  const ReradiationMatrix& f = *s.materials[0].reradiation;
  EXPECT_TRUE(f.measured());
  // ~450 nm excitation into ~500 nm emission: 0.3 per 100 nm-wide CSV bin = 0.003 per nm, x 5 nm.
  EXPECT_NEAR(f(ReradiationMatrix::binOf(445), ReradiationMatrix::binOf(500)), 0.015, 0.001);
  EXPECT_EQ(f(ReradiationMatrix::binOf(500), ReradiationMatrix::binOf(450)), 0.0); // no anti-Stokes
  const std::string got =
      errorOf(scene(sphere + dir + "bad.csv</matrix></fluorescence></sphere>\n"));
  EXPECT_NE(
      got.find(dir + "bad.csv:2: expected 4 cells (excitation wavelength and 3 values), found 3"),
      std::string::npos)
      << got;
}

} // namespace
} // namespace nx

namespace nx {
namespace {

// A table that ends inside the traced range warns, naming the element, the spectrum and both
// ranges; extrapolate="zero" or "hold" chooses (hold keeps the end values), silently; a use of a
// <spectrum> definition may choose for it.
TEST(SceneBuilder, TablesEndingInsideTheTracedRangeWarnUnlessTheyChoose) {
  const std::string sphere = "<sphere><center>0,0,0</center><radius>1</radius>";
  const RenderScene s = build(scene(
      "<spectrum name=\"paint\">400:0.2, 700:0.6</spectrum>\n" + sphere +
      "<material>matte</material><reflectance>paint</reflectance></sphere>\n" + sphere +
      "<material>matte</material><reflectance extrapolate=\"hold\">paint</reflectance></sphere>\n" +
      sphere + "<material>matte</material><reflectance extrapolate=\"zero\">400:0.2, 700:0.6" +
      "</reflectance></sphere>\n" + sphere +
      "<material>matte</material><emission>D65</emission></sphere>\n" + sphere +
      "<material>matte</material><emission>A</emission></sphere>\n"));
  const auto visible = extrapolationWarnings(s, 360, 830);
  ASSERT_EQ(visible.size(), 1u);
  EXPECT_EQ(visible[0], "t.scn:4: warning: spectrum 'nm:value pairs' is tabulated over 400-700 nm "
                        "and this render traces 360-830 nm: it is 0 beyond its table (write "
                        "extrapolate=\"zero\" or extrapolate=\"hold\" on the element to choose)");
  const auto infrared = extrapolationWarnings(s, 360, 1005);
  ASSERT_EQ(infrared.size(), 2u);
  EXPECT_NE(infrared[1].find("t.scn:8: warning: spectrum 'D65' is tabulated over 300-830 nm and "
                             "this render traces 360-1005 nm"),
            std::string::npos)
      << infrared[1];
  EXPECT_TRUE(extrapolationWarnings(s, 400, 700).empty());
  // Values beyond the table: zero, or held (the second sphere), or A's formula beyond 830 nm.
  ASSERT_GE(s.shapes(ShapeKind::Sphere).size(), 5u);
  const auto reflectanceAt = [&](int sphereIndex, double nm) {
    return s.materials[s.shapes(ShapeKind::Sphere)[sphereIndex].material].reflectance(nm);
  };
  EXPECT_DOUBLE_EQ(reflectanceAt(0, 900), 0.0);
  EXPECT_DOUBLE_EQ(reflectanceAt(1, 900), 0.6);
  EXPECT_DOUBLE_EQ(reflectanceAt(1, 350), 0.2);
  EXPECT_DOUBLE_EQ(reflectanceAt(2, 900), 0.0);
  EXPECT_GT(s.emission[s.shapes(ShapeKind::Sphere)[4].emission](1000),
            s.emission[s.shapes(ShapeKind::Sphere)[4].emission](830));
  EXPECT_EQ(errorOf(scene(sphere + "<material>matte</material><emission extrapolate=\"last\">D65"
                                   "</emission></sphere>\n")),
            "t.scn:4: expected extrapolate=\"zero\" or extrapolate=\"hold\", found 'last'");
}

// A lamp measured with dark subtraction has small negative values: refused as an emission, or
// with negative="clamp" set to 0 and counted in a warning (CSV and pairs, inline and in a
// named <spectrum>); reflectance tables are clamped the same way.
TEST(SceneBuilder, NegativeClampSetsMeasuredNegativesToZeroAndCountsThem) {
  const std::string csv = ::testing::TempDir() + "/lamp_dark_subtracted.csv";
  std::ofstream(csv) << "nm,value\n380,-0.002\n400,0.1\n500,0.8\n600,0.9\n700,-0.001\n800,0.2\n";
  const std::string light =
      "<light><position>0,5,0</position><color>1,1,1</color><emission csv=\"" + csv + "\"";
  EXPECT_NE(errorOf(scene(light + "/></light>")).find("expected an emission within [0"),
            std::string::npos);
  const RenderScene s = build(scene(light + " negative=\"clamp\"/></light>"));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("t.scn:4: warning: 2 of 6 values of '" + csv +
                               "' were negative (down to -0.002) and were set to 0"),
            std::string::npos)
      << s.warnings[0];
  const auto& point = std::get<PointLight>(s.lights[0]);
  EXPECT_EQ(point.intensity(700), 0.0);
  EXPECT_NEAR(point.intensity(500), 0.8, 1e-6);
  const RenderScene named = build(scene(
      "<spectrum name=\"lamp\" negative=\"clamp\">400:0.5, 500:-0.01, 600:0.5</spectrum>" +
      std::string("<light><position>0,5,0</position><color>1,1,1</color><emission>lamp</emission>"
                  "</light>")));
  ASSERT_EQ(named.warnings.size(), 1u);
  EXPECT_NE(named.warnings[0].find("1 of 3 values of 'nm:value pairs'"), std::string::npos);
  EXPECT_NE(
      errorOf(scene(light + " negative=\"zero\"/></light>")).find("expected negative=\"clamp\""),
      std::string::npos);
}

} // namespace
} // namespace nx
