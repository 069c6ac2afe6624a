#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "accel/shape_kinds.h"
#include "core/error.h"
#include "integrators/materials/material_kind.h"
#include "integrators/scene_reader.h"
#include "io/scene_desc.h"
#include "support/errors.h"

namespace nx {
namespace {

// "<sphere>, <plane>, ...": the shape kinds' elements as the loader's messages list them (from
// the registry, so that a new kind edits no expected message).
std::string shapeTags() {
  std::string tags;
  for (const ShapeKindSpec& k : shapeKinds())
    tags += (tags.empty() ? "<" : ", <") + std::string(k.name) + ">";
  return tags;
}

// A valid scene whose line 3 onwards can be replaced by the body under test.
std::string scene(const std::string& body,
                  const std::string& settings = "<mode>spectral_mcpt</mode>") {
  return "<scene>\n"
         "<settings><xres>8</xres><yres>6</yres>" +
         settings +
         "</settings>\n"
         "<camera><position>0, 0, 0</position><look_at>0, 0, 1</look_at></camera>\n" +
         body + "</scene>\n";
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  return s.replace(s.find(from), from.size(), to);
}

std::string errorOf(const std::string& text) {
  return test::errorMessage([&] { parseScene(text, "t.scn"); });
}

TEST(SceneLoader, ReadsTheThesisScene) {
  const SceneDesc d = loadScene(NX_SOURCE_DIR "/scenes/thesis.scn");
  EXPECT_EQ(d.settings.width, 400);
  EXPECT_EQ(d.settings.height, 225);
  EXPECT_EQ(d.settings.mode, RenderMode::SpectralMcpt);
  EXPECT_EQ(d.settings.depth, 10);
  EXPECT_EQ(d.settings.samples, 4096);
  EXPECT_EQ(d.settings.outputPath, "test_smcpt_d65_fluo_4096sp.bmp");
  ASSERT_TRUE(d.settings.illuminant.has_value());
  EXPECT_EQ(d.settings.illuminant->name, "bbd65");
  EXPECT_EQ(d.camera.position, Vec3d(0, 5, -6));
  EXPECT_EQ(d.camera.lookAt, Vec3d(0, 2, 2));
  EXPECT_NEAR(d.camera.fovDegrees, 81.8, 1e-12);
  ASSERT_EQ(d.objects.size(), 6u);
  EXPECT_EQ(d.objects[0].shape, "plane");
  EXPECT_EQ(*d.objects[0].geometry.get<Vec3d>("normal"), Vec3d(0, 0, -1));
  EXPECT_EQ(*d.objects[0].geometry.number("distance"), -10);
  EXPECT_FALSE(d.objects[0].emission.has_value()); // <emission>0.0</emission>: not a light
  EXPECT_EQ(d.objects[2].material, "diamond");
  EXPECT_EQ(d.objects[3].params.get<SpectrumDesc>("reflectance")->name, "orange");
  const auto* fluorescence = d.objects[3].params.get<FluorescenceDesc>("fluorescence");
  ASSERT_NE(fluorescence, nullptr);
  EXPECT_EQ(*fluorescence->absorptionName, "blue");
  EXPECT_EQ(*fluorescence->stokesNm, 220);
  EXPECT_EQ(d.objects[5].emission->name, "bbd65");
  EXPECT_EQ(*d.objects[5].geometry.number("radius"), 6);
  EXPECT_EQ(d.objects[5].loc.line, 61);
}

TEST(SceneLoader, NumberListsAcceptAnySeparators) {
  const SceneDesc d = parseScene(
      scene("<sphere><center>1,2 ,  3</center><radius>2</radius><material>matte</material>"
            "<reflectance>gray</reflectance></sphere>\n"),
      "t.scn");
  EXPECT_EQ(*d.objects[0].geometry.get<Vec3d>("center"), Vec3d(1, 2, 3));
  const SceneDesc e =
      parseScene(scene("<sphere><center>1 2 3</center><radius>2</radius><material>matte</material>"
                       "<reflectance>gray</reflectance></sphere>\n"),
                 "t.scn");
  EXPECT_EQ(*e.objects[0].geometry.get<Vec3d>("center"), Vec3d(1, 2, 3));
}

TEST(SceneLoader, SamplesTagAndItsThesisTypo) {
  EXPECT_EQ(parseScene(scene("", "<mode>rt</mode><sampl>9</sampl>"), "t").settings.samples, 9);
  EXPECT_EQ(parseScene(scene("", "<mode>rt</mode><samp1>4</samp1>"), "t").settings.samples, 4);
}

TEST(SceneLoader, Extensions) {
  const SceneDesc d = loadScene(NX_SOURCE_DIR "/scenes/extensions.scn");
  ASSERT_EQ(d.spectra.size(), 2u);
  EXPECT_EQ(d.spectra[0].name, "paint");
  EXPECT_EQ(d.spectra[0].spectrum.kind, SpectrumDesc::Kind::Pairs);
  EXPECT_EQ(d.spectra[0].spectrum.nm.size(), 5u);
  EXPECT_EQ(d.spectra[1].spectrum.kind, SpectrumDesc::Kind::CsvFile);
  EXPECT_EQ(d.spectra[1].spectrum.path, std::string(NX_SOURCE_DIR) + "/scenes/data/warm_led.csv");
  EXPECT_EQ(d.settings.bands.count(), 14);
  EXPECT_EQ(d.settings.seed, 7u);
  EXPECT_EQ(d.settings.background->number, 0.05);
  EXPECT_EQ(d.camera.fovDegrees, 40);
  EXPECT_EQ(d.camera.up, Vec3d(0.1, 1, 0));
  EXPECT_EQ(*d.objects[1].params.number("roughness"), 0.5);
  EXPECT_EQ(d.objects[2].params.get<IorDesc>("ior")->kind, IorDesc::Kind::Cauchy);
  EXPECT_EQ(d.objects[4].emissionScale, 6);
  EXPECT_EQ(d.objects[0].params.get<SpectrumDesc>("reflectance")->number, 0.5);
}

TEST(SceneLoader, SecondCameraIsIgnoredWithAWarning) {
  const SceneDesc d = parseScene(
      scene("<camera><position>9, 9, 9</position><look_at>0, 0, 0</look_at></camera>\n"), "t.scn");
  EXPECT_EQ(d.camera.position, Vec3d(0, 0, 0));
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_EQ(d.warnings[0], "t.scn:4: warning: a second <camera> is ignored (the first one wins)");
}

struct BadCase {
  const char* what;
  std::string text;
  std::string message;
};

// Every error class: the message names the file, the line, what was expected and what was found.
TEST(SceneLoader, ErrorsNameFileLineExpectedAndFound) {
  const std::string sphereTail =
      "<material>matte</material><reflectance>gray</reflectance></sphere>\n";
  const std::vector<BadCase> cases = {
      {"empty file", "",
       "t.scn:1: expected an XML document with a <scene> element, found an empty file"},
      {"blank file", "  \n\n ",
       "t.scn:1: expected an XML document with a <scene> element, found an empty file"},
      {"syntax", "<scene>\n<settings>\n<xres>8</yres>\n</settings></scene>",
       "t.scn:3: expected well-formed XML, found a syntax error (Start-end tags mismatch)"},
      {"truncated", "<scene>\n<settings><xres>8</xres>\n",
       "t.scn:2: expected well-formed XML, found a syntax error"},
      {"binary", std::string("\x01\x02\xff\xfe<\x00>", 7), "t.scn:1: expected well-formed XML"},
      {"plain text", "just some words\nand more\n",
       "t.scn:1: expected an XML document with a <scene> element, found no XML element"},
      {"wrong root", "<scen></scen>", "t.scn:1: expected the root element <scene>, found <scen>"},
      {"unknown top tag", scene("<shpere></shpere>\n"),
       "t.scn:4: expected one of <settings>, <camera>, <light>, " + shapeTags() +
           ", <material>, <spectrum>, found <shpere>"},
      {"unknown child", scene("<sphere><centre>0,0,0</centre></sphere>\n"),
       "t.scn:4: expected one of <material>, <color>, <reflectance>, <roughness>, <ior>, "
       "<fluorescence>, <eta>, <k>, <metal>, <alpha>, <alpha_u>, <alpha_v>, <sigma>, <coating>, "
       "<emission>, "
       "<center>, <radius>, <medium> inside <sphere>, found <centre>"},
      {"repeated tag", scene("<sphere><radius>1</radius><radius>2</radius></sphere>\n"),
       "t.scn:4: expected one <radius>, found a second <radius>"},
      {"unknown attribute", scene("<sphere colour=\"red\"></sphere>\n"),
       "t.scn:4: expected only the attribute(s) name, group on <sphere>, found attribute 'colour'"},
      {"stray text", scene("hello\n"),
       "t.scn:4: expected only elements inside <scene>, found text 'hello'"},
      {"missing settings",
       "<scene>\n<camera><position>0,0,0</position><look_at>0,0,1</look_at></camera>\n</scene>",
       "t.scn:1: expected a <settings> element, found none"},
      {"missing camera",
       "<scene>\n<settings><xres>8</xres><yres>6</yres><mode>rt</mode></settings>\n</scene>",
       "t.scn:1: expected a <camera> element, found none"},
      {"missing xres", "<scene>\n<settings><yres>6</yres><mode>rt</mode></settings>\n</scene>",
       "t.scn:2: expected <xres> inside <settings>, found none"},
      {"bad mode", scene("", "<mode>pathtracing</mode>"),
       "t.scn:2: expected a mode rt, mcpt or spectral_mcpt, found 'pathtracing'"},
      {"zero resolution",
       "<scene>\n<settings><xres>0</xres><yres>6</yres><mode>rt</mode></settings></scene>",
       "t.scn:2: expected a width in pixels in [1, 65536], found '0'"},
      {"negative resolution",
       "<scene>\n<settings><xres>8</xres><yres>-6</yres><mode>rt</mode></settings></scene>",
       "t.scn:2: expected a height in pixels in [1, 65536], found '-6'"},
      {"fractional resolution",
       "<scene>\n<settings><xres>8.5</xres><yres>6</yres><mode>rt</mode></settings></scene>",
       "t.scn:2: expected a whole number (a width in pixels) in <xres>, found '8.5'"},
      {"absurd samples", scene("", "<mode>rt</mode><sampl>99999999999</sampl>"),
       "t.scn:2: expected a sample count per pixel in [1, 1073741824], found '99999999999'"},
      {"wrong count", scene("<sphere><center>1, 2</center><radius>1</radius>" + sphereTail),
       "t.scn:4: expected 3 numbers (a sphere centre x, y, z) in <center>, found 2 ('1, 2')"},
      {"not a number", scene("<sphere><center>1, 2, x</center><radius>1</radius>" + sphereTail),
       "t.scn:4: expected a sphere centre x, y, z in <center>, found 'x'"},
      {"non-finite", scene("<sphere><center>1, 2, 3</center><radius>nan</radius>" + sphereTail),
       "t.scn:4: expected a radius in <radius>, found 'nan' (not a finite value)"},
      {"overflow", scene("<sphere><center>1e400, 2, 3</center><radius>1</radius>" + sphereTail),
       "t.scn:4: expected a sphere centre x, y, z in <center>, found '1e400' (not a finite value)"},
      {"huge coordinate",
       scene("<sphere><center>1e13, 2, 3</center><radius>1</radius>" + sphereTail),
       "t.scn:4: expected a sphere centre x, y, z with coordinates within +/-1e12, found '1e13, 2, "
       "3'"},
      {"negative radius", scene("<sphere><center>0,0,0</center><radius>-1</radius>" + sphereTail),
       "t.scn:4: expected a radius in (0, 1e+12], found '-1'"},
      {"zero normal",
       scene("<plane><normal>0, 0, "
             "0</normal><distance>1</distance><material>matte</material></plane>\n"),
       "t.scn:4: expected a non-zero plane normal, found '0, 0, 0'"},
      {"degenerate triangle",
       scene("<triangle><vA>0,0,0</vA><vB>1,1,1</vB><vC>2,2,2</vC><material>matte</material></"
             "triangle>\n"),
       "t.scn:4: expected a triangle with non-zero area, found collinear vertices"},
      {"missing material", scene("<sphere><center>0,0,0</center><radius>1</radius></sphere>\n"),
       "t.scn:4: expected <material> inside <sphere>, found none"},
      {"unknown material",
       scene("<sphere><center>0,0,0</center><radius>1</radius><material>velvet</material></"
             "sphere>\n"),
       "t.scn:4: expected a material " + materialKindList() +
           " or the id of a <material id=\"...\"> of the scene, found 'velvet'"},
      {"colour count",
       scene("<sphere><center>0,0,0</center><radius>1</radius><material>matte</material><color>1, "
             "0</color></sphere>\n"),
       "t.scn:4: expected 3 to 4 numbers (R, G, B[, A]) in <color>, found 2 ('1, 0')"},
      {"colour range",
       scene("<sphere><center>0,0,0</center><radius>1</radius><material>matte</"
             "material><color>1.5, 0, 0, 1</color></sphere>\n"),
       "t.scn:4: expected reflectance colour channels in [0, 1], found '1.5, 0, 0, 1'"},
      {"negative emission",
       scene("<sphere><center>0,0,0</center><radius>1</radius><material>matte</"
             "material><emission>-2</emission></sphere>\n"),
       "t.scn:4: expected a non-negative value in <emission>, found '-2'"},
      {"negative stokes",
       scene("<sphere><center>0,0,0</center><radius>1</radius><material>matte</material>"
             "<fluorescence><absorption>blue</absorption><stokes>-20</stokes></fluorescence></"
             "sphere>\n"),
       "t.scn:4: expected a Stokes shift in nm in [0, 1000], found '-20'"},
      {"missing stokes",
       scene("<sphere><center>0,0,0</center><radius>1</radius><material>matte</material>"
             "<fluorescence><absorption>blue</absorption></fluorescence></sphere>\n"),
       "t.scn:4: expected <stokes> inside <fluorescence>, found none"},
      {"yield range",
       scene("<sphere><center>0,0,0</center><radius>1</radius><material>matte</"
             "material><fluorescence>"
             "<absorption>blue</absorption><stokes>20</stokes><yield>1.5</yield></fluorescence></"
             "sphere>\n"),
       "t.scn:4: expected a quantum yield in [0, 1], found '1.5'"},
      {"roughness range",
       scene("<sphere><center>0,0,0</center><radius>1</radius><material>metal</"
             "material><roughness>2</roughness></sphere>\n"),
       "t.scn:4: expected a roughness in [0, 1], found '2'"},
      {"bad ior name",
       scene("<sphere><center>0,0,0</center><radius>1</radius><material>glass</"
             "material><ior>crystal</ior></sphere>\n"),
       "t.scn:4: expected a named glass bk7, diamond or fused_silica, found 'crystal'"},
      {"bad sellmeier",
       scene("<sphere><center>0,0,0</center><radius>1</radius><material>glass</"
             "material><ior>sellmeier: 1, 2</ior></sphere>\n"),
       "t.scn:4: expected sellmeier: B1, B2, B3, C1, C2, C3 (6 numbers), found 2 numbers"},
      {"ior below one",
       scene("<sphere><center>0,0,0</center><radius>1</radius><material>glass</material><ior>0.5</"
             "ior></sphere>\n"),
       "t.scn:4: expected an index of refraction in [1, 10], found '0.5'"},
      {"bad bands", scene("", "<mode>rt</mode><bands>400:705:10</bands>"),
       "t.scn:2: bands '400:705:10': expected END - START to be a multiple of STEP, found "
       "400:705:10"},
      {"bad pairs",
       scene("<sphere><center>0,0,0</center><radius>1</radius><material>matte</material>"
             "<reflectance>400:0.1, 500</reflectance></sphere>\n"),
       "t.scn:4: expected nm:value pairs such as 400:0.2, 500:0.7, found '500'"},
      {"spectrum without name", scene("<spectrum>400:0.1, 500:0.2</spectrum>\n"),
       "t.scn:4: expected a name=\"...\" attribute on <spectrum>, found none"},
      {"spectrum defined twice",
       scene("<spectrum name=\"a\">0.5</spectrum>\n<spectrum name=\"a\">0.2</spectrum>\n"),
       "t.scn:5: expected a new spectrum name, found 'a' defined twice"},
      {"bad fov",
       replaced(scene(""), "<look_at>0, 0, 1</look_at>",
                "<look_at>0, 0, 1</look_at><fov>180</fov>"),
       "t.scn:3: expected a horizontal field of view in degrees in (0, 179], found '180'"},
      {"camera looks at itself",
       replaced(scene(""), "<look_at>0, 0, 1</look_at>", "<look_at>0, 0, 0</look_at>"),
       "t.scn:3: expected a look_at point different from the camera position, found '0, 0, 0'"},
      {"element inside leaf", scene("<sphere><center><x>1</x></center></sphere>\n"),
       "t.scn:4: expected text inside <center>, found element <x>"},
      {"huge resolution",
       "<scene>\n<settings><xres>65536</xres><yres>65536</yres><mode>rt</mode><bands>400:700:1</"
       "bands>"
       "</settings>\n<camera><position>0,0,0</position><look_at>0,0,1</look_at></camera></scene>",
       "t.scn:2: expected a resolution whose buffers fit in memory, found 65536x65536 with 301 "
       "bands"},
  };
  for (const auto& c : cases) {
    const std::string got = errorOf(c.text);
    EXPECT_EQ(got.rfind(c.message, 0), 0u)
        << c.what << "\n  got:      " << got << "\n  expected: " << c.message;
  }
}

// Entities: the predefined five and character references are resolved; an undefined entity is
// an error at its element (pugixml kept "&foo;" as literal text, e.g. in a file name).
TEST(SceneLoader, EntitiesResolvedOrRefused) {
  const std::string head =
      "<scene>\n<settings><xres>8</xres><yres>6</yres><mode>spectral_mcpt</mode></settings>\n"
      "<camera><position>0, 0, 0</position><look_at>0, 0, 1</look_at></camera>\n";
  const SceneDesc d = parseScene(
      head + "<spectrum name=\"a&amp;b&#x41;&#66;\">0.5</spectrum>\n"
             "<sphere><center>0,0,&#53;</center><radius>1</radius><material>matte</material>"
             "<reflectance>a&amp;bAB</reflectance></sphere>\n</scene>\n",
      "t.scn");
  EXPECT_EQ(d.spectra[0].name, "a&bAB");
  EXPECT_EQ((*d.objects[0].geometry.get<Vec3d>("center"))[2], 5.0);
  EXPECT_EQ(errorOf(head + "<sphere><center>0,0,5</center><radius>1</radius><material>matte"
                           "</material><reflectance>&foo;</reflectance></sphere>\n</scene>\n"),
            "t.scn:4: expected only the entities &amp; &lt; &gt; &quot; &apos; and character "
            "references, found the undefined entity '&foo;'");
  EXPECT_EQ(errorOf(head + "<sphere><center>0,0,5</center><radius>1</radius><material>matte"
                           "</material><reflectance csv=\"&bar;.csv\"/></sphere>\n</scene>\n"),
            "t.scn:4: expected only the entities &amp; &lt; &gt; &quot; &apos; and character "
            "references, found the undefined entity '&bar;'");
}

TEST(SceneLoader, FilesThatAreNotScenes) {
  EXPECT_THROW(loadScene("/nonexistent/x.scn"), Error);
  try {
    loadScene(NX_SOURCE_DIR "/scenes");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              NX_SOURCE_DIR "/scenes: expected a scene file, found a directory");
  }
}

// 200,000 nested elements: a clear error quickly, no stack overflow.
TEST(SceneLoader, DeepNestingIsRefusedQuickly) {
  std::string text = "<scene>";
  for (int i = 0; i < 200000; ++i) text += "<a>";
  for (int i = 0; i < 200000; ++i) text += "</a>";
  text += "</scene>";
  const auto start = std::chrono::steady_clock::now();
  const std::string got = errorOf(text);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_EQ(got.rfind("t.scn:1: expected one of <settings>", 0), 0u) << got;
}

} // namespace
} // namespace nx

namespace nx {
namespace {

// <sensor> in <settings>: measured responses from a CSV file (relative to the scene), Gaussian
// bands from centres and FWHMs, boxes with their own edges.
TEST(SceneLoader, SensorForms) {
  const std::string dir = ::testing::TempDir() + "sensor_scene";
  std::filesystem::create_directories(dir);
  {
    std::ofstream csv(dir + "/srf.csv");
    csv << "nm,a,b\n500,0,0\n510,1,0\n520,0,0\n600,0,0\n610,0,1\n620,0,0\n";
  }
  const auto settings = [&](const std::string& sensor) {
    return "<scene><settings><xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode>" + sensor +
           "</settings><camera><position>0,0,-5</position><look_at>0,0,0</look_at></camera>"
           "</scene>";
  };
  {
    std::ofstream scene(dir + "/s.scn");
    scene << settings("<sensor csv=\"srf.csv\"/>");
  }
  const SceneDesc csv = loadScene(dir + "/s.scn");
  ASSERT_EQ(csv.settings.bands.count(), 2);
  EXPECT_EQ(csv.settings.bands.channel(1).name, "b");
  EXPECT_NEAR(csv.settings.bands.centroid(1), 610, 1e-9);
  const SceneDesc g =
      parseScene(settings("<sensor gaussian=\"450, 550\" fwhm=\"10, 20\"/>"), "t.scn");
  ASSERT_EQ(g.settings.bands.count(), 2);
  EXPECT_DOUBLE_EQ(g.settings.bands.fwhm(1), 20);
  const SceneDesc boxes = parseScene(settings("<sensor boxes=\"400-420, 420-460\"/>"), "t.scn");
  EXPECT_DOUBLE_EQ(boxes.settings.bands.centroid(1), 440);
  EXPECT_EQ(
      test::errorMessage([&] { parseScene(settings("<sensor gaussian=\"450\"/>"), "t.scn"); }),
      "t.scn:1: expected a fwhm=\"...\" attribute with gaussian=\"...\", found none");
}

} // namespace
} // namespace nx
