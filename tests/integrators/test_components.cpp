// Component images (--aov components, lightgroups): closed forms in the fluorescent furnace,
// splits that sum to the radiance, exact zeros where a class cannot occur, light groups against
// renders of each light alone, resume.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "spectra/reradiation_matrix.h"
#include "support/errors.h"
#include "support/furnace_solution.h"
#include "support/render_checks.h"

namespace nx {
namespace {

using RM = ReradiationMatrix;

RenderOptions componentOptions(bool components = true, bool lightGroups = true) {
  RenderOptions o;
  o.components = components;
  o.lightGroups = lightGroups;
  return o;
}

int layerIndex(const Film& film, const std::string& name) {
  for (int l = 0; l < film.layerCount(); ++l)
    if (film.layerName(l) == name) return l;
  ADD_FAILURE() << "no layer " << name;
  return 0;
}

// Mean and standard error over pixels of layer `name`, band b.
test::RunningStats layerStats(const Film& film, const std::string& name, int b) {
  const int l = layerIndex(film, name);
  test::RunningStats s;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) s.add(film.layerMean(x, y, l, b));
  return s;
}

// Every band of layer `name` equals expected(band) within 5 standard errors, with power (a
// standard error below `precision` of the larger of the value and 0.05).
void expectLayer(const Film& film, const std::string& name,
                 const std::function<double(int)>& expected, double precision) {
  for (int b = 0; b < film.bands().count(); ++b) {
    const test::RunningStats s = layerStats(film, name, b);
    const double e = expected(b);
    // (an absolute slack of 1e-4 for the model's far tails, ~1e-5 of the radiance here, which
    // 256 samples rarely reach)
    EXPECT_LT(std::abs(s.mean - e), 5 * s.standardError() + 1e-4)
        << name << " band " << film.bands().centroid(b) << ": mean " << s.mean << " expected " << e;
    EXPECT_LT(s.standardError(), precision * std::max(e, 0.05))
        << name << " band " << film.bands().centroid(b);
  }
}

// The layers `parts` sum to the radiance in every pixel and band, to float rounding.
void expectSplitSumsToTotal(const Film& film, const std::vector<std::string>& parts) {
  double worst = 0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x)
      for (int b = 0; b < film.bands().count(); ++b) {
        double sum = 0;
        for (const std::string& p : parts) sum += film.layerMean(x, y, layerIndex(film, p), b);
        const double total = film.bandMean(x, y, b);
        worst = std::max(worst, std::abs(sum - total) / std::max(total, 1e-30));
      }
  EXPECT_LT(worst, 1e-5) << parts.front() << " + ...";
}

std::string furnaceScene(int samples, const std::string& emission = "0.5",
                         const std::string& stokes = "220") {
  return "<scene><settings><xres>12</xres><yres>12</yres><mode>spectral_mcpt</mode><depth>3</"
         "depth><sampl>" +
         std::to_string(samples) +
         "</sampl></settings><camera><position>0,0,0</position><look_at>0,0,1</look_at></camera>"
         "<sphere><center>0,0,0</center><radius>1</radius><material>matte</material>"
         "<reflectance>0.5</reflectance><emission>" +
         emission + "</emission><fluorescence><absorption>blue</absorption><stokes>" + stokes +
         "</stokes></fluorescence></sphere></scene>";
}

// The closed fluorescent furnace (rho 0.5, emission with bin means le, the model's matrix M,
// elastic D): per bin, the reflected component is Le / (1 - D), the fluoresced one the rest of
// L = (I - D - M^T)^-1 Le; the direct component is Le + (D + M^T) Le, the indirect one the
// rest. Each split sums to the radiance to float rounding.
void expectFurnaceComponents(const RM& m, const std::vector<double>& le, const std::string& scene) {
  const double rho = 0.5;
  const std::vector<double> total = test::furnaceRadiance(m, rho, le);
  std::vector<double> reflected(RM::kBins), direct(RM::kBins);
  for (int o = 0; o < RM::kBins; ++o) {
    reflected[o] = le[o] / (1 - m.elastic(o, rho));
    double fromM = 0;
    for (int i = 0; i < RM::kBins; ++i) fromM += m(i, o) * le[i];
    direct[o] = le[o] + m.elastic(o, rho) * le[o] + fromM;
  }
  const RenderOutput out = renderText(scene, componentOptions());
  const Film& f = out.film;
  ASSERT_EQ(f.layerCount(), 5);
  const Sensor& bands = f.bands();
  expectLayer(
      f, "reflected", [&](int b) { return test::bandOfBins(reflected, bands, b); }, 0.02);
  expectLayer(
      f, "fluoresced",
      [&](int b) {
        return test::bandOfBins(total, bands, b) - test::bandOfBins(reflected, bands, b);
      },
      0.035);
  expectLayer(
      f, "direct", [&](int b) { return test::bandOfBins(direct, bands, b); }, 0.02);
  expectLayer(
      f, "indirect",
      [&](int b) { return test::bandOfBins(total, bands, b) - test::bandOfBins(direct, bands, b); },
      0.035);
  // Fluorescence is a real share here (the test separates something).
  double fluoresced = 0;
  for (int b = 0; b < bands.count(); ++b)
    fluoresced = std::max(fluoresced, layerStats(f, "fluoresced", b).mean);
  EXPECT_GT(fluoresced, 0.05);
  expectSplitSumsToTotal(f, {"reflected", "fluoresced"});
  expectSplitSumsToTotal(f, {"direct", "indirect"});
  expectSplitSumsToTotal(f, {"light.default"});
}

TEST(Components, FluorescentFurnaceClosedForms) {
  expectFurnaceComponents(RM::fromModel({460, 220, 20, 10, 1, 1}),
                          std::vector<double>(RM::kBins, 0.5), furnaceScene(256));
}

// The same under a royal-blue LED's narrow band onto a dye absorbing there (Stokes 80), where
// the excitation is drawn from the column and the light's spectrum and combined by MIS: the
// class of each part (the guided event's own) keeps the splits exact.
TEST(Components, FluorescentFurnaceUnderANarrowLedClosedForms) {
  expectFurnaceComponents(RM::fromModel({460, 80, 20, 10, 1, 1}),
                          test::binMeans(test::royalBlueLed),
                          furnaceScene(512, test::royalBlueLedText(), "80"));
}

// The same random numbers: the radiance of a component render is the plain render's.
TEST(Components, RadianceIsThePlainRendersOwn) {
  const RenderOutput plain = renderText(furnaceScene(8));
  const RenderOutput split = renderText(furnaceScene(8), componentOptions());
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x)
      for (int b = 0; b < plain.film.bands().count(); ++b)
        ASSERT_EQ(split.film.bandMean(x, y, b), plain.film.bandMean(x, y, b)) << x << "," << y;
}

const char* kLitSphere =
    "<scene><settings><xres>16</xres><yres>16</yres><mode>spectral_mcpt</mode><depth>4</depth>"
    "<sampl>16</sampl><background>0.3</background></settings>"
    "<camera><position>0,0,-4</position><look_at>0,0,0</look_at><fov>30</fov></camera>"
    "<sphere><center>0,0,0</center><radius>1</radius><material>matte</material>"
    "<reflectance>0.7</reflectance></sphere>";

// Without fluorescence the fluoresced component is exactly 0 and the reflected one is the
// radiance. A convex object under the background has no indirect light at all (after it a
// path leaves the scene): exactly 0; a floor beside it brings some.
TEST(Components, ExactZerosWhereAClassCannotOccur) {
  const RenderOutput convex = renderText(std::string(kLitSphere) + "</scene>", componentOptions());
  const Film& f = convex.film;
  const int fl = layerIndex(f, "fluoresced"), ind = layerIndex(f, "indirect");
  double lit = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int b = 0; b < f.bands().count(); ++b) {
        ASSERT_EQ(f.layerMean(x, y, fl, b), 0.0);
        ASSERT_EQ(f.layerMean(x, y, ind, b), 0.0);
        lit += f.bandMean(x, y, b);
      }
  EXPECT_GT(lit, 0.0);
  expectSplitSumsToTotal(f, {"reflected"});
  expectSplitSumsToTotal(f, {"direct"});

  const RenderOutput floor =
      renderText(std::string(kLitSphere) +
                     "<plane><normal>0,1,0</normal><distance>-1</distance>"
                     "<material>matte</material><reflectance>0.5</reflectance></plane></scene>",
                 componentOptions());
  EXPECT_GT(layerStats(floor.film, "indirect", 10).mean, 0.0);
  expectSplitSumsToTotal(floor.film, {"direct", "indirect"});
}

// Two lamps in groups and an ungrouped background: the groups' layers sum to the radiance, and
// each equals a render with that light alone (z-test on the image means of every band).
TEST(Components, LightGroupsEqualRendersOfEachLightAlone) {
  auto scene = [](bool key, bool fill, bool sky) {
    return std::string("<scene><settings><xres>16</xres><yres>16</yres><mode>spectral_mcpt</"
                       "mode><depth>4</depth><sampl>64</sampl>") +
           (sky ? "<background>0.2</background>" : "") +
           "</settings><camera><position>0,1,-5</position><look_at>0,0.5,0</look_at><fov>40</"
           "fov></camera><plane><normal>0,1,0</normal><distance>0</distance><material>matte</"
           "material><reflectance>0.6</reflectance></plane>"
           "<sphere><center>0,0.7,0</center><radius>0.7</radius><material>matte</material>"
           "<reflectance>0.5</reflectance></sphere>"
           "<sphere" +
           (fill ? " group=\"fill\"" : "") +
           "><center>-2,2,-1</center><radius>0.4</radius><material>matte</material><reflectance>"
           "0.2</reflectance>" +
           (fill ? "<emission>6</emission>" : "") + "</sphere>" +
           (key ? "<light group=\"key\"><position>2,3,-2</position><color>1,1,1</color><emission>"
                  "40</emission></light>"
                : "") +
           "</scene>";
  };
  const RenderOutput all = renderText(scene(true, true, true), componentOptions(false, true));
  const Film& f = all.film;
  ASSERT_EQ(f.layerCount(), 3);
  EXPECT_EQ(f.layerName(0), "light.default"); // the background, ungrouped
  EXPECT_EQ(f.layerName(1), "light.fill");
  EXPECT_EQ(f.layerName(2), "light.key");
  expectSplitSumsToTotal(f, {"light.default", "light.fill", "light.key"});
  const std::pair<const char*, std::string> alone[] = {
      {"light.key", scene(true, false, false)},
      {"light.fill", scene(false, true, false)},
      {"light.default", scene(false, false, true)}};
  for (const auto& [layer, text] : alone) {
    const RenderOutput one = renderText(text);
    for (int b = 0; b < f.bands().count(); b += 3) {
      const test::RunningStats a = layerStats(f, layer, b), o = bandStats(one.film, b);
      const double se = std::hypot(a.standardError(), o.standardError());
      EXPECT_GT(o.mean, 0.0) << layer;
      EXPECT_LT(std::abs(a.mean - o.mean), 5 * se)
          << layer << " band " << b << ": " << a.mean << " vs " << o.mean << " se " << se;
    }
  }
}

// A resumed component render ends with the uninterrupted one's layers (to the rounding of the
// stored means); a resume with other layers is refused.
TEST(Components, ResumeContinuesTheLayers) {
  const RenderScene scene = buildRenderScene(parseScene(furnaceScene(8), "t.scn"));
  RenderOptions o = componentOptions();
  const RenderOutput whole = render(scene, o);
  o.samples = 4;
  const RenderOutput first = render(scene, o);
  const Film stored = filmFromImage(toSpectralImage(first.film), 0, 8);
  ASSERT_EQ(stored.layerCount(), 5);
  RenderOptions r = componentOptions();
  r.samples = 8;
  r.resumeFrom = &stored;
  const RenderOutput resumed = render(scene, r);
  for (int l = 0; l < 5; ++l)
    for (int b = 0; b < whole.film.bands().count(); ++b) {
      const double w = whole.film.layerMean(5, 5, l, b);
      EXPECT_NEAR(resumed.film.layerMean(5, 5, l, b), w, 1e-6 * std::max(1.0, w));
    }
  RenderOptions other;
  other.samples = 8;
  other.resumeFrom = &stored;
  EXPECT_EQ(test::errorMessage([&] { render(scene, other); }),
            "cannot continue a render with other component layers: it holds 5 (reflected, ...), "
            "this one asks for 0 (use the same --aov as the first run)");
}

// Whitted ray tracing has no path classes: refused.
TEST(Components, RefusedInWhittedMode) {
  const RenderScene scene = buildRenderScene(parseScene(
      "<scene><settings><xres>4</xres><yres>4</yres><mode>rt</mode></settings><camera><position>"
      "0,0,-4</position><look_at>0,0,0</look_at></camera><sphere><center>0,0,0</center><radius>1"
      "</radius><material>matte</material><reflectance>0.5</reflectance></sphere></scene>",
      "t.scn"));
  EXPECT_EQ(test::errorMessage([&] { render(scene, componentOptions()); }),
            "component images (--aov components, lightgroups) need a path-traced mode "
            "(spectral_mcpt or mcpt), found rt (Whitted ray tracing has no path classes)");
}

} // namespace
} // namespace nx
