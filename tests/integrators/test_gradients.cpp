// Differentiated renders (docs/inverse.md): for every kind of differentiable parameter, the
// forward-mode gradient agrees with a central finite difference of renders with common random
// numbers (same seed) within the noise of their per-pixel difference, with power; reverse mode
// gives the adjoint-weighted sum of the forward images; the tape's sweep; the refusals.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>

#include "integrators/gradients/gradient_setup.h"
#include "integrators/gradients/light_gradients.h"
#include "integrators/gradients/path_gradients.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "support/constant_map.h"
#include "support/errors.h"
#include "support/statistics.h"
#include "support/test_scale.h"

namespace nx {
namespace {

// A floor, a sphere and a sphere lamp; `floor`, `sphere` and `extra` are the floor's material
// elements, the sphere's and anything more (lights, a background).
std::string scene(const std::string& floor, const std::string& sphere, const std::string& lamp,
                  const std::string& extra = "", int samples = 64,
                  const std::string& camera = "0,1,-5") {
  return "<scene><settings><xres>24</xres><yres>24</yres><mode>spectral_mcpt</mode><depth>8</"
         "depth><sampl>" +
         std::to_string(samples) +
         "</sampl><bands>400:700:50</bands></settings><camera><position>" + camera +
         "</position><look_at>0,0.5,0</look_at><fov>40</fov></camera><plane><normal>0,1,0</"
         "normal><distance>0</distance>" +
         floor + "</plane><sphere><center>0,0.7,0</center><radius>0.7</radius>" + sphere +
         "</sphere><sphere><center>-1.5,2.5,-1</center><radius>0.5</radius><material>matte</"
         "material><reflectance>0</reflectance>" +
         lamp + "</sphere>" + extra + "</scene>";
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

const std::string kLamp = "<emission scale=\"2e-3\">blackbody:5000</emission>";
const std::string kMatte = "<material>matte</material><reflectance>0.6</reflectance>";

// One differentiable parameter: the scene at a value, the value and the difference step.
struct Family {
  std::function<std::string(double)> text;
  double at, step;
  int samples = 0; ///< samples per pixel (0: the scene's)
  /// The largest standard error of the comparison allowed, as a share of the gradient.
  double power = 0.03;
  /// Richardson's extrapolation of central differences at steps h and h/2, (4 D(h/2) - D(h)) / 3
  /// (truncation error O(h^4)): for parameters that move the sampling (free-flight distances,
  /// scattering events), where common random numbers decorrelate and a small step is noisy.
  bool richardson = false;
  /// The parameter's name in the scene (Scene.parameters()): when given, the tangents are the
  /// library's set-up by name (gradientSetup, its own step), else a central difference of the
  /// texts at +-step.
  std::string name = {};
};

// `f` differentiated by name, through the library's set-up.
Family named(const std::string& name, Family f) {
  f.name = name;
  return f;
}

RenderScene built(const std::string& text) {
  return buildRenderScene(parseScene(text, "t.scn"));
}

// The tangents of the family's parameter at `at` (one slot, a central difference of
// resolved scenes).
SceneTangents tangentsOf(const Family& f, const RenderScene& base) {
  if (!f.name.empty())
    return gradientSetup(parseScene(f.text(f.at), "t.scn"), {f.name}, base, true).tangents;
  const RenderScene plus = resolveRenderScene(parseScene(f.text(f.at + f.step), "t.scn"));
  const RenderScene minus = resolveRenderScene(parseScene(f.text(f.at - f.step), "t.scn"));
  SceneTangents t = SceneTangents::sizedFor(base);
  const RenderScene* scenes[] = {&plus, &minus};
  const double w[] = {0.5 / f.step, -0.5 / f.step};
  addTangentSlot(t, "p", base, scenes, w);
  return t;
}

// Forward mode against the central difference of two renders with the same seed: per band,
// the mean over pixels of (gradient - difference) within 5 standard errors, and the test has
// power: among the bands carrying at least half the largest gradient, the best resolved has
// that standard error below f.power of its gradient (3%: a gradient 15% off fails). (Not the
// largest band alone: where two bands carry nearly equal gradients, an absorption band
// resolved to 2% and an emission band to 8%, which one is largest changed with the sampler.)
// Returns the image-mean gradient per band.
std::vector<double> expectGradientMatchesDifference(const Family& f,
                                                    const RenderOptions& base = {}) {
  const RenderScene s = built(f.text(f.at));
  const SceneTangents t = tangentsOf(f, s);
  EXPECT_TRUE(t.inert.empty()) << "the parameter changes nothing";
  RenderOptions plain = base;
  plain.samples = f.samples > 0 ? test::scaledSamples(f.samples) : 0;
  RenderOptions o = plain;
  o.gradients = &t;
  const RenderOutput g = render(s, o);
  EXPECT_EQ(g.stats.gradientZeroValues, 0u);
  const RenderOutput plus = render(built(f.text(f.at + f.step)), plain);
  const RenderOutput minus = render(built(f.text(f.at - f.step)), plain);
  std::optional<RenderOutput> halfPlus, halfMinus;
  if (f.richardson) {
    halfPlus = render(built(f.text(f.at + f.step / 2)), plain);
    halfMinus = render(built(f.text(f.at - f.step / 2)), plain);
  }
  const int nb = g.film.bands().count();
  std::vector<double> means;
  std::vector<double> errors;
  for (int b = 0; b < nb; ++b) {
    test::RunningStats d, grad, radiance;
    for (int y = 0; y < 24; ++y)
      for (int x = 0; x < 24; ++x) {
        radiance.add(g.film.bandMean(x, y, b));
        double fd = (plus.film.bandMean(x, y, b) - minus.film.bandMean(x, y, b)) / (2 * f.step);
        if (f.richardson)
          fd =
              (4 * (halfPlus->film.bandMean(x, y, b) - halfMinus->film.bandMean(x, y, b)) / f.step -
               fd) /
              3;
        const double gr = g.film.layerMean(x, y, 0, b);
        d.add(gr - fd);
        grad.add(gr);
      }
    // Beyond the noise: the renders' single-precision rounding, which common random numbers
    // do not cancel (about 1e-6 of the radiance per render).
    const double rounding = 1e-5 * radiance.mean / (2 * f.step);
    EXPECT_LE(std::abs(d.mean), 5 * d.standardError() + rounding)
        << "band " << b << ": gradient " << grad.mean << ", difference " << grad.mean - d.mean
        << " +- " << d.standardError();
    means.push_back(grad.mean);
    errors.push_back(d.standardError());
  }
  double strongest = 0;
  for (double m : means) strongest = std::max(strongest, std::abs(m));
  EXPECT_GT(strongest, 0.0);
  double bestResolved = INFINITY;
  for (size_t b = 0; b < means.size(); ++b)
    if (std::abs(means[b]) >= 0.5 * strongest)
      bestResolved = std::min(bestResolved, errors[b] / std::abs(means[b]));
  EXPECT_LT(bestResolved, test::scaledPower(f.power)) << "the test cannot resolve the gradient";
  return means;
}

TEST(Gradients, TapeSweepSumsEachEventOverTheContributionsAfterIt) {
  GradientTape tape;
  GradientSink sink;
  sink.tape = &tape;
  SampledSpectrum c1 = SampledSpectrum::filled(1.0f), c2 = SampledSpectrum::filled(2.0f);
  sink.event(0, 1, 0.5f); // before both contributions
  sink.local(1, 2, 3.0f); // the first contribution's own
  sink.add(c1, PathClass{});
  sink.event(0, 1, 0.25f);                  // before the second only
  sink.add(SampledSpectrum(), PathClass{}); // a black one records nothing
  sink.add(c2, PathClass{});
  float d[2][kLanes] = {};
  tape.sweep([&](uint32_t slot, int lane, float v) { d[slot][lane] += v; });
  EXPECT_FLOAT_EQ(d[0][1], 0.5f * (1 + 2) + 0.25f * 2);
  EXPECT_FLOAT_EQ(d[1][2], 3.0f * 1);
  EXPECT_FLOAT_EQ(d[0][0], 0.0f);
  EXPECT_FLOAT_EQ(sink.L[0], 3.0f);
}

TEST(Gradients, MatteReflectanceMatchesDifference) {
  expectGradientMatchesDifference(
      named("objects[0].reflectance", {[](double p) {
                                         return scene("<material>matte</material><reflectance>" +
                                                          num(p) + "</reflectance>",
                                                      kMatte, kLamp);
                                       },
                                       0.5, 0.02}));
}

TEST(Gradients, ReflectanceKnotMatchesDifference) {
  // A knot of a tabulated reflectance: its derivative is a hat function over the knot.
  expectGradientMatchesDifference(
      {[](double p) {
         return scene("<material>matte</material><reflectance>400:0.3, 550:" + num(p) +
                          ", 700:0.8</reflectance>",
                      kMatte, kLamp);
       },
       0.5, 0.02});
}

TEST(Gradients, CoatedDiffuseReflectanceMatchesDifference) {
  // rho enters the coat's internal reflections too: f ~ rho / (1 - rho F_i).
  expectGradientMatchesDifference(
      named("objects[1].reflectance", {[](double p) {
                                         return scene(kMatte,
                                                      "<material>coated</material><reflectance>" +
                                                          num(p) + "</reflectance>",
                                                      kLamp);
                                       },
                                       0.7, 0.02}));
}

TEST(Gradients, RoughDiffuseReflectanceMatchesDifference) {
  // rho enters EON's multiple scattering as rho^2 E / (1 - rho (1 - E)): its slope is the
  // model's own and depends on the directions (SurfaceBsdf::reflectanceLogSlope).
  expectGradientMatchesDifference(
      named("objects[1].reflectance", {[](double p) {
                                         return scene(kMatte,
                                                      "<material>rough_matte</material><sigma>1"
                                                      "</sigma><reflectance>" +
                                                          num(p) + "</reflectance>",
                                                      kLamp);
                                       },
                                       0.6, 0.02}));
}

TEST(Gradients, GlassTintMatchesDifference) {
  expectGradientMatchesDifference(
      {[](double p) {
         return scene(kMatte, "<material>glass</material><reflectance>" + num(p) + "</reflectance>",
                      kLamp);
       },
       0.8, 0.02});
}

TEST(Gradients, AreaLampScaleMatchesDifference) {
  expectGradientMatchesDifference(
      named("objects[2].emission_scale", {[](double p) {
                                            return scene(kMatte, kMatte,
                                                         "<emission scale=\"" + num(p) +
                                                             "\">blackbody:5000</emission>");
                                          },
                                          2e-3, 1e-4}));
}

TEST(Gradients, EmissionKnotAndSpotLightMatchDifference) {
  // A knot of a lamp's tabulated spectrum (sparse: two knots per wavelength), and a spot's scale.
  expectGradientMatchesDifference({[](double p) {
                                     return scene(kMatte, kMatte,
                                                  "<emission scale=\"5e-3\">380:1, 480:" + num(p) +
                                                      ", 520:0.1, 800:0.1</emission>");
                                   },
                                   1, 0.05});
  expectGradientMatchesDifference(
      {[](double p) {
         return scene(kMatte, kMatte, kLamp,
                      "<light type=\"spot\"><position>1,3,-2</position><look_at>0,0,0</look_at>"
                      "<cone_angle>30</cone_angle><emission scale=\"" +
                          num(p) + "\">D65</emission></light>");
       },
       0.05, 0.005});
}

TEST(Gradients, PointLightAndBackgroundMatchDifference) {
  expectGradientMatchesDifference(
      {[](double p) {
         return scene(kMatte, kMatte, kLamp,
                      "<light><position>1,3,-2</position><color>1,1,1</color><emission scale=\"" +
                          num(p) + "\">D65</emission></light>");
       },
       0.02, 0.002});
  expectGradientMatchesDifference({[](double p) {
                                     std::string t = scene(kMatte, kMatte, kLamp);
                                     t.insert(t.find("</settings>"),
                                              "<background>" + num(p) + "</background>");
                                     return t;
                                   },
                                   0.002, 0.0002});
}

// The sphere fluoresces (model parameters); `field` is the one varied.
std::string fluorescent(const std::string& material, const std::string& field, double p) {
  std::string fields = "<absorption>460</absorption><stokes>90</stokes><width>25</width>"
                       "<skew>5</skew><yield>0.8</yield><peak>0.9</peak>";
  const std::string open = "<" + field + ">", close = "</" + field + ">";
  const size_t a = fields.find(open), b = fields.find(close);
  fields.replace(a, b + close.size() - a, open + num(p) + close);
  return "<material>" + material + "</material><reflectance>0.4</reflectance><fluorescence>" +
         fields + "</fluorescence>";
}

TEST(Gradients, FluorescenceModelParametersMatchDifferences) {
  // Under a blue-heavy lamp so the dye's emission is well lit.
  const std::string lamp = "<emission scale=\"5e-3\">380:1, 480:1, 520:0.1, 800:0.1</emission>";
  // Steps: wide where the matrix is linear in the parameter (yield, peak), else a compromise
  // between the difference's truncation error (h^2) and its noise (the re-radiation choice
  // moves with the parameter, so common random numbers decorrelate, ~1/h).
  // The tangents are the library's set-up by each field's parameter name.
  for (const auto& [field, name, at, step] :
       std::vector<std::tuple<std::string, std::string, double, double>>{
           {"yield", "quantum_yield", 0.8, 0.15},
           {"stokes", "stokes_nm", 90, 1},
           {"absorption", "absorption_nm", 460, 1},
           {"width", "width_nm", 25, 0.5},
           {"skew", "skew", 5, 0.25},
           {"peak", "peak_absorptance", 0.9, 0.08}}) {
    SCOPED_TRACE(field);
    const std::string f = field;
    const double a = at, h = step;
    // The library's tangent is of a small step; the renders' difference, at a wide one, is
    // extrapolated (Richardson) where the matrix is not linear in the parameter.
    const bool nonlinear = field != "yield" && field != "peak";
    expectGradientMatchesDifference(
        named("objects[1].fluorescence." + name, {[f, lamp](double p) {
                                                    return scene(kMatte, fluorescent("matte", f, p),
                                                                 lamp, "", 64, "0,0.9,-2.2");
                                                  },
                                                  a, h, 1024, 0.04, nonlinear}));
  }
}

TEST(Gradients, CoatedFluorescenceMatchesDifference) {
  const std::string lamp = "<emission scale=\"5e-3\">380:1, 480:1, 520:0.1, 800:0.1</emission>";
  expectGradientMatchesDifference({[lamp](double p) {
                                     return scene(kMatte, fluorescent("coated", "stokes", p), lamp,
                                                  "", 64, "0,0.9,-2.2");
                                   },
                                   90, 1, 1024, 0.04});
  // rho of a fluorescent surface: its elastic part (1 - a) rho
  expectGradientMatchesDifference({[lamp](double p) {
                                     std::string m = fluorescent("coated", "yield", 0.8);
                                     m.replace(m.find("0.4"), 3, num(p));
                                     return scene(kMatte, m, lamp);
                                   },
                                   0.4, 0.02, 512});
}

// The sphere holds a medium behind a thin glass wall (or an interface); `medium` are its
// elements.
std::string inMedium(const std::string& medium, const std::string& wall = "interface") {
  return "<material>" + wall + "</material><medium>" + medium + "</medium>";
}

TEST(Gradients, MediumCoefficientsMatchDifferences) {
  // sigma_a and sigma_s of a scattering medium (free flights, their transmittance to the
  // surfaces behind, shadow rays through it), and its phase function's g. sigma_a is a weight
  // only (distances follow sigma_s), so common random numbers keep a small step exact; sigma_s
  // and g move the sampling: wide steps, extrapolated, and a weaker power (20% off fails).
  const auto fog = [](double a, double sc, double g) {
    return inMedium("<sigma_a>" + num(a) + "</sigma_a><sigma_s>" + num(sc) + "</sigma_s><g>" +
                    num(g) + "</g>");
  };
  {
    SCOPED_TRACE("sigma_a");
    expectGradientMatchesDifference(
        {[&](double p) { return scene(kMatte, fog(p, 1.5, 0.3), kLamp); }, 0.4, 0.02, 256});
  }
  {
    SCOPED_TRACE("sigma_s");
    expectGradientMatchesDifference(
        {[&](double p) { return scene(kMatte, fog(0.4, p, 0.3), kLamp); }, 1.5, 0.4, 512, 0.04,
         true});
  }
  {
    SCOPED_TRACE("g");
    expectGradientMatchesDifference(
        {[&](double p) { return scene(kMatte, fog(0.4, 1.5, p), kLamp); }, 0.3, 0.15, 512, 0.04,
         true});
  }
}

TEST(Gradients, MediumDyeMatchesDifferences) {
  // A dye dissolved in a clear liquid behind thin glass: its peak (concentration) and its
  // model's parameters (re-emission bins, its absorption along every segment).
  const std::string lamp = "<emission scale=\"5e-3\">380:1, 480:1, 520:0.1, 800:0.1</emission>";
  const auto dyed = [](double peak, double stokes) {
    return inMedium("<sigma_a>0.05</sigma_a><sigma_s>0.2</sigma_s><fluorescence><absorption>460<"
                    "/absorption><stokes>" +
                        num(stokes) + "</stokes><width>25</width><yield>0.8</yield><peak>" +
                        num(peak) + "</peak></fluorescence>",
                    "thin_glass");
  };
  {
    SCOPED_TRACE("peak");
    expectGradientMatchesDifference(
        {[&](double p) { return scene(kMatte, dyed(p, 90), lamp, "", 64, "0,0.9,-2.2"); }, 0.8, 0.3,
         1024, 0.04, true});
  }
  {
    // The dye's emission shift is a small net change (light moves between bands), so the
    // difference resolves it to 15% here (a gradient 75% off fails); at 16384 samples per
    // pixel (3%) it agrees as well (docs/inverse.md).
    SCOPED_TRACE("stokes");
    expectGradientMatchesDifference(
        {[&](double p) { return scene(kMatte, dyed(0.8, p), lamp, "", 64, "0,0.9,-2.2"); }, 90, 6,
         1024, 0.15, true});
  }
}

TEST(Gradients, ThinWallTintInAMediaSceneMatchesDifference) {
  // The wall's tint scales paths through it and shadow rays crossing it.
  expectGradientMatchesDifference(
      {[](double p) {
         return scene(kMatte,
                      "<material>thin_glass</material><reflectance>" + num(p) +
                          "</reflectance><medium><sigma_a>0.1</sigma_a><sigma_s>0.5</sigma_s></"
                          "medium>",
                      kLamp);
       },
       0.8, 0.02, 256});
}

// A CSV concentration map in the temporary directory (its name made from `tag`).
std::string concentrationFile(const std::string& tag,
                              const std::vector<std::vector<double>>& rows) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("nx_concentration_" + tag + ".csv")).string();
  std::ofstream out(path);
  for (const auto& r : rows) {
    for (size_t i = 0; i < r.size(); ++i) out << (i ? ", " : "") << num(r[i]);
    out << "\n";
  }
  return path;
}

// The fluorescent sphere with a concentration map (or none) and peak absorptance `peak`.
std::string dyedCard(const std::string& map, double peak) {
  const std::string lamp = "<emission scale=\"5e-3\">380:1, 480:1, 520:0.1, 800:0.1</emission>";
  return scene(kMatte,
               "<material>matte</material><reflectance>0.4</reflectance><fluorescence><absorption>"
               "460</absorption><stokes>90</stokes><width>25</width><yield>0.8</yield><peak>" +
                   num(peak) + "</peak>" +
                   (map.empty() ? "" : "<concentration>" + map + "</concentration>") +
                   "</fluorescence>",
               lamp, "", 256, "0,0.9,-2.2");
}

TEST(Gradients, UniformConcentrationIsAScaledPeakAbsorptance) {
  // k everywhere: absorptance k a, cells k M, elastic (1 - k a) rho - the model with a peak
  // absorptance k a_max. Two renders of different seeds agree per band within the noise.
  const std::string map = concentrationFile("uniform", {{0.4, 0.4}, {0.4, 0.4}});
  RenderOptions a, b;
  a.seed = 1, b.seed = 2;
  const RenderOutput withMap = render(built(dyedCard(map, 0.9)), a);
  const RenderOutput scaled = render(built(dyedCard("", 0.36)), b);
  // Whitted ray tracing (rt) samples the scaled column too.
  auto rt = [](std::string t) {
    t.replace(t.find("spectral_mcpt"), 13, "rt");
    return t;
  };
  const RenderOutput rtMap = render(built(rt(dyedCard(map, 0.9))), a);
  const RenderOutput rtScaled = render(built(rt(dyedCard("", 0.36))), b);
  for (int band = 0; band < withMap.film.bands().count(); ++band) {
    test::RunningStats d;
    for (int py = 0; py < 24; ++py)
      for (int px = 0; px < 24; ++px)
        d.add(rtMap.film.bandMean(px, py, band) - rtScaled.film.bandMean(px, py, band));
    EXPECT_LE(std::abs(d.mean), 5 * d.standardError() + 1e-12) << "rt band " << band;
  }
  for (int band = 0; band < withMap.film.bands().count(); ++band) {
    test::RunningStats d, y;
    for (int py = 0; py < 24; ++py)
      for (int px = 0; px < 24; ++px) {
        d.add(withMap.film.bandMean(px, py, band) - scaled.film.bandMean(px, py, band));
        y.add(scaled.film.bandMean(px, py, band));
      }
    EXPECT_LT(std::abs(d.mean), 5 * d.standardError()) << "band " << band;
    EXPECT_LT(d.standardError(), 0.02 * y.mean) << "band " << band;
  }
  // and it is not the unscaled dye
  const RenderOutput full = render(built(dyedCard("", 0.9)), b);
  double sumMap = 0, sumFull = 0;
  for (int py = 0; py < 24; ++py)
    for (int px = 0; px < 24; ++px)
      sumMap += withMap.film.bandMean(px, py, 3), sumFull += full.film.bandMean(px, py, 3);
  EXPECT_GT(std::abs(sumMap - sumFull), 0.05 * sumFull);
}

TEST(Gradients, ConcentrationMapValuesMatchDifferences) {
  // A 3 x 3 map on the sphere: d image / d value (the bilinear weights at each hit, 1 / k for
  // a re-radiation, -a rho / D for the elastic part) against differences of that value.
  const std::vector<std::vector<double>> base = {{0.2, 0.5, 0.8}, {0.6, 0.3, 0.9}, {0.4, 0.7, 0.5}};
  for (const auto& [row, col] : std::vector<std::pair<int, int>>{{1, 1}, {1, 0}}) {
    SCOPED_TRACE(std::to_string(row) + "," + std::to_string(col));
    auto text = [&, row = row, col = col](double p) {
      auto rows = base;
      rows[static_cast<size_t>(row)][static_cast<size_t>(col)] = p;
      return dyedCard(concentrationFile("value" + num(p), rows), 0.9);
    };
    const double at = base[static_cast<size_t>(row)][static_cast<size_t>(col)];
    const RenderScene s = built(text(at));
    const RenderScene changed = resolveRenderScene(parseScene(text(at + 0.05), "t.scn"));
    SceneTangents t = SceneTangents::sizedFor(s);
    const uint32_t first = addConcentrationSlots(t, "map", s, changed);
    ASSERT_EQ(t.slots(), first + 9);
    // The slot of this value alone, as a one-slot render sees it.
    // The render is nearly linear in k (light re-radiated twice on the sphere is k^2): a wide
    // step keeps the difference's noise low (the re-radiation choice moves with k).
    RenderOptions plain;
    plain.samples = 512;
    RenderOptions o = plain;
    o.gradients = &t;
    const RenderOutput g = render(s, o);
    const RenderOutput plus = render(built(text(at + 0.15)), plain);
    const RenderOutput minus = render(built(text(at - 0.15)), plain);
    const int slot = static_cast<int>(first) + row * 3 + col;
    double strongest = 0, error = 0;
    for (int b = 0; b < g.film.bands().count(); ++b) {
      test::RunningStats d, grad;
      for (int py = 0; py < 24; ++py)
        for (int px = 0; px < 24; ++px) {
          const double fd = (plus.film.bandMean(px, py, b) - minus.film.bandMean(px, py, b)) / 0.3;
          d.add(g.film.layerMean(px, py, slot, b) - fd);
          grad.add(g.film.layerMean(px, py, slot, b));
        }
      EXPECT_LE(std::abs(d.mean), 5 * d.standardError() + 1e-9) << "band " << b;
      if (std::abs(grad.mean) > strongest)
        strongest = std::abs(grad.mean), error = d.standardError();
    }
    EXPECT_GT(strongest, 0.0);
    EXPECT_LT(error, 0.05 * strongest);
  }
}

// The floor's reflectance as the parameter (at `at`), at `samples` per pixel.
Family matteFloor(int samples, double at) {
  return {[samples](double p) {
            return scene("<material>matte</material><reflectance>" + num(p) + "</reflectance>",
                         kMatte, kLamp, "", samples);
          },
          at, 0.02};
}

TEST(Gradients, ReverseModeIsTheAdjointWeightedForwardImage) {
  const Family f = matteFloor(16, 0.5);
  const RenderScene s = built(f.text(f.at));
  const SceneTangents t = tangentsOf(f, s);
  RenderOptions o;
  o.gradients = &t;
  const RenderOutput forward = render(s, o);
  const int nb = forward.film.bands().count();
  // A loss weighing band 2 by 1 and band 4 by -0.5 in the left half of the image.
  std::vector<float> adjoint(24 * 24 * static_cast<size_t>(nb), 0.0f);
  double expected = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 12; ++x) {
      adjoint[(static_cast<size_t>(y) * 24 + x) * nb + 2] = 1.0f;
      adjoint[(static_cast<size_t>(y) * 24 + x) * nb + 4] = -0.5f;
      expected += forward.film.layerMean(x, y, 0, 2) - 0.5 * forward.film.layerMean(x, y, 0, 4);
    }
  o.adjoint = &adjoint;
  const RenderOutput reverse = render(s, o);
  ASSERT_EQ(reverse.gradient.size(), 1u);
  EXPECT_NEAR(reverse.gradient[0], expected, 1e-4 * std::abs(expected));
  EXPECT_GT(reverse.gradientVariance[0], 0.0);
  EXPECT_LT(std::sqrt(reverse.gradientVariance[0]), 0.2 * std::abs(expected));
  // another tiling groups the sums differently: the same to rounding (the thread count changes
  // nothing at all: tests/python/test_gradients.py)
  RenderOptions one = o;
  one.tileSize = 8;
  EXPECT_NEAR(render(s, one).gradient[0], reverse.gradient[0], 1e-9 * std::abs(expected));
}

TEST(Gradients, ConductorRoughnessMatchesDifference) {
  // A rough gold sphere: d ln f / d alpha = d ln D / d alpha + d ln G2 / d alpha at next-event
  // estimation and at the sampled direction (visible-normal sampling held); the roughness moves
  // the sampling, so a wide step, extrapolated. alpha_u alone (anisotropic) too.
  const auto gold = [](double u, double v) {
    return scene(kMatte,
                 "<material>conductor</material><metal>gold</metal><alpha_u>" + num(u) +
                     "</alpha_u><alpha_v>" + num(v) + "</alpha_v>",
                 kLamp, "", 64, "0,0.9,-2.2");
  };
  {
    SCOPED_TRACE("alpha");
    expectGradientMatchesDifference(
        {[&](double p) { return gold(p, p); }, 0.3, 0.1, 512, 0.04, true});
  }
  {
    SCOPED_TRACE("alpha_u");
    expectGradientMatchesDifference(
        {[&](double p) { return gold(p, 0.15); }, 0.3, 0.1, 512, 0.04, true});
  }
}

TEST(Gradients, RefusesWhatIsNotDifferentiated) {
  // Roughness from 0 (a smooth metal's delta lobe) and a rough dielectric's.
  for (const std::string& material :
       {std::string("<material>conductor</material><metal>gold</metal>"),
        std::string("<material>glass</material>")}) {
    const double at = material.find("gold") != std::string::npos ? 0.0 : 0.2;
    const Family rough{[material](double p) {
                         return scene(kMatte, material + "<alpha>" + num(p) + "</alpha>", kLamp);
                       },
                       at, 0.01};
    const RenderScene s = built(rough.text(at));
    const RenderScene plus = resolveRenderScene(parseScene(rough.text(at + 0.01), "t.scn"));
    SceneTangents t = SceneTangents::sizedFor(s);
    const RenderScene* scenes[] = {&plus, &s};
    const double w[] = {100.0, -100.0};
    EXPECT_NE(test::errorMessage([&] {
                addTangentSlot(t, "p", s, scenes, w);
              }).find("p: not differentiable: it changes the microfacet roughness of a"),
              std::string::npos)
        << material;
  }
  // An adjoint of the wrong size, gradients with component layers.
  const Family f = matteFloor(4, 0.5);
  const RenderScene m = built(f.text(f.at));
  const SceneTangents t = tangentsOf(f, m);
  RenderOptions o;
  o.gradients = &t;
  std::vector<float> adjoint(10, 0.0f);
  o.adjoint = &adjoint;
  EXPECT_NE(
      test::errorMessage([&] { render(m, o); }).find("the adjoint image holds 10 values, expected"),
      std::string::npos);
  o.adjoint = nullptr;
  o.components = true;
  EXPECT_NE(test::errorMessage([&] { render(m, o); }).find("gradients cannot be combined"),
            std::string::npos);
}

// Every light kind is declared to the gradient code (a kind it did not list threw
// std::bad_variant_access; a new one now fails to compile: build.light_kind_needs_...): beside
// a point, a spot and an environment light a reflectance is differentiated, the point's and
// the spot's intensities are the differentiated spectra, and a change of the environment map
// between the builds is refused by name.
TEST(Gradients, EveryLightKindIsHandledOrRefusedByName) {
  const std::string map = test::writeConstantMap("gradient_sky.exr", 4, 2, "350:1050:100", 0.05f);
  auto text = [&](double reflectance, double skyScale) {
    return scene(
        "<material>matte</material><reflectance>" + num(reflectance) + "</reflectance>", kMatte,
        kLamp,
        "<light><position>1,3,-1</position><color>1,1,1</color><emission>1</emission></light>"
        "<light type=\"spot\"><position>-1,3,-2</position><look_at>0,0,0</look_at>"
        "<cone_angle>30</cone_angle><color>1,1,1</color><emission>2</emission></light>"
        "<light type=\"environment\"><file>" +
            map + "</file><scale>" + num(skyScale) + "</scale></light>",
        4);
  };
  const RenderScene base = built(text(0.5, 1));
  ASSERT_EQ(base.lights.size(), 3u);
  EXPECT_NE(differentiatedLightSpectrum(base.lights[0]), nullptr);
  EXPECT_NE(differentiatedLightSpectrum(base.lights[1]), nullptr);
  EXPECT_EQ(differentiatedLightSpectrum(base.lights[2]), nullptr);
  const RenderScene plus = resolveRenderScene(parseScene(text(0.51, 1), "t.scn"));
  SceneTangents t = SceneTangents::sizedFor(base);
  const RenderScene* scenes[] = {&plus, &base};
  const double w[] = {100.0, -100.0};
  (void)addTangentSlot(t, "objects[0].reflectance", base, scenes, w);
  RenderOptions o;
  o.gradients = &t;
  EXPECT_EQ(render(base, o).film.layerCount(), 1);
  const RenderScene brighter = resolveRenderScene(parseScene(text(0.5, 2), "t.scn"));
  const RenderScene* changed[] = {&brighter, &base};
  SceneTangents t2 = SceneTangents::sizedFor(base);
  EXPECT_NE(test::errorMessage([&] {
              addTangentSlot(t2, "lights[2].scale", base, changed, w);
            }).find("lights[2].scale: not differentiable: it changes an environment map"),
            std::string::npos);
}

TEST(Gradients, ZeroReflectanceIsReported) {
  // d f / d rho exists at rho = 0, but the estimator divides by rho: counted and warned.
  const Family f = matteFloor(4, 0.0);
  const RenderScene s = built(f.text(f.at));
  const RenderScene plus = resolveRenderScene(parseScene(f.text(0.02), "t.scn"));
  SceneTangents t = SceneTangents::sizedFor(s);
  const RenderScene* scenes[] = {&plus, &s};
  const double w[] = {50.0, -50.0};
  addTangentSlot(t, "p", s, scenes, w);
  RenderOptions o;
  o.gradients = &t;
  const RenderOutput out = render(s, o);
  EXPECT_GT(out.stats.gradientZeroValues, 0u);
  const std::vector<std::string> w2 = warningsOf(out.stats);
  ASSERT_FALSE(w2.empty());
  EXPECT_NE(w2.front().find("differentiated value of 0"), std::string::npos);
}

} // namespace
} // namespace nx
