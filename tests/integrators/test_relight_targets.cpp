// Relit ground truth and relighting targets (docs/relighting.md): a relit image carries its
// reflected and fluoresced components, which sum to its radiance and equal a direct component
// render (also for shifts that stay inside one excitation bin and one band); a render told its
// targets relit to a narrow lamp is no noisier than 1.5x a direct render (and 2x noisier
// without them, so that the check means something), still relights to any other spectrum
// unbiased, and relighting warns about a narrow spectrum without targets.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "integrators/relight_image.h"
#include "integrators/relight_targets.h"
#include "io/spectral_exr.h"
#include "support/errors.h"
#include "support/relight_checks.h"

namespace nx {
namespace {

// A render under S1 relit to S2, and a direct render under S2 with its component layers.
struct RelitAndDirect {
  SpectralImage relit, direct;
};

RelitAndDirect relitAndDirect(const std::string& under, const std::string& to, double stepNm,
                              const std::string& (*edit)(std::string&) = nullptr) {
  std::string a = benchScene(under, "", 256), b = benchScene(to, "", 256);
  if (edit) edit(a), edit(b);
  const SpectralImage img = toSpectralImage(renderRelightable(a, stepNm).film);
  EXPECT_TRUE(img.relight.split);
  RelitAndDirect out;
  out.relit = relightImage(img, {binned(img, "lamp", to)});
  RenderOptions o;
  o.seed = 7;
  o.components = true;
  out.direct = toSpectralImage(renderText(b, o).film);
  return out;
}

// Per pixel and band the components sum to the radiance (float rounding of a few sums).
void expectComponentsSum(const SpectralImage& relit) {
  ASSERT_EQ(relit.layers.size(), 2u);
  EXPECT_EQ(relit.layers[0].name, "reflected");
  EXPECT_EQ(relit.layers[1].name, "fluoresced");
  double fluoresced = 0;
  for (size_t k = 0; k < relit.radiance.size(); ++k) {
    const double sum = relit.layers[0].values[k] + relit.layers[1].values[k];
    EXPECT_NEAR(sum, relit.radiance[k], 1e-5 * std::abs(relit.radiance[k]) + 1e-12) << k;
    EXPECT_GE(relit.layers[1].values[k], 0.0f) << k;
    fluoresced += relit.layers[1].values[k];
  }
  EXPECT_GT(fluoresced, 0.0) << "the sphere fluoresces";
}

TEST(RelitComponents, SumToTheRadianceAndEqualDirectComponentRenders) {
  const RelitAndDirect r = relitAndDirect(kLampS1, kLampS2, 5);
  expectComponentsSum(r.relit);
  expectSameBands(r.relit, r.direct, "S1 relit to S2");
  expectSameBands(r.relit, r.direct, "reflected", "reflected");
  expectSameBands(r.relit, r.direct, "fluoresced", "fluoresced", 0.1);
}

// A Stokes shift of 5 nm on a 10 nm excitation grid and 20 nm bands: much of the re-radiated
// light leaves and arrives within one bin and one band, and is still told from reflected light.
const std::string& smallShift(std::string& scene) {
  const std::string from = "<stokes>100</stokes>", to = "<stokes>5</stokes>";
  scene.replace(scene.find(from), from.size(), to);
  return scene;
}

TEST(RelitComponents, ShiftsWithinOneBinAreSplitExactly) {
  const RelitAndDirect r = relitAndDirect(kLampS1, kLampS2, 10, smallShift);
  expectComponentsSum(r.relit);
  expectSameBands(r.relit, r.direct, "reflected", "reflected");
  expectSameBands(r.relit, r.direct, "fluoresced", "fluoresced", 0.1);
}

// The split survives the EXR (the fluoresced channels and nxrender.relightDiagonal); a file
// without the attribute relights without components; a fluoresced channel without it, or a
// fluoresced part outside its band's range, is refused.
TEST(RelitComponents, FileRoundTripAndOlderFiles) {
  const SpectralImage img = toSpectralImage(renderRelightable(benchScene(kLampS1, "", 8), 5).film);
  const std::string path = ::testing::TempDir() + "nx_relit_components.exr";
  writeSpectralExr(path, img);
  const SpectralImage back = readSpectralExr(path);
  ASSERT_TRUE(back.relight.split);
  ASSERT_EQ(back.relight.size(), img.relight.size());
  int parts = 0;
  for (size_t e = 0; e < img.relight.size(); ++e) {
    EXPECT_TRUE(sameEntry(back.relight.entries[e], img.relight.entries[e])) << e;
    parts += img.relight.entries[e].fluoresced;
  }
  EXPECT_GT(parts, 0) << "the sphere's shift within the 20 nm bands needs fluoresced parts";
  const SpectralImage a = relightImage(img, {binned(img, "lamp", kLampS2)});
  const SpectralImage b = relightImage(back, {binned(back, "lamp", kLampS2)});
  ASSERT_EQ(b.layers.size(), 2u);
  EXPECT_EQ(a.layers[1].values, b.layers[1].values);

  // An older file: totals only (the parts dropped, the attribute gone).
  SpectralImage old = img;
  RelightLayers& rl = old.relight;
  const size_t pixels = img.sampleCount.size();
  RelightLayers kept = rl;
  kept.entries.clear(), kept.values.clear(), kept.halfDifferences.clear();
  kept.split = false;
  for (size_t g = 0; g < rl.sources.size(); ++g)
    for (size_t e = 0; e < rl.size(); ++e) {
      if (rl.entries[e].fluoresced) continue;
      if (g == 0) kept.entries.push_back({rl.entries[e].row, rl.entries[e].bin, 0, 0});
      const size_t k = (g * rl.size() + e) * pixels;
      kept.values.insert(kept.values.end(), rl.values.begin() + k, rl.values.begin() + k + pixels);
      kept.halfDifferences.insert(kept.halfDifferences.end(), rl.halfDifferences.begin() + k,
                                  rl.halfDifferences.begin() + k + pixels);
    }
  old.relight = kept;
  writeSpectralExr(path, old);
  const SpectralImage oldBack = readSpectralExr(path);
  EXPECT_FALSE(oldBack.relight.split);
  const SpectralImage oldRelit = relightImage(oldBack, {binned(oldBack, "lamp", kLampS2)});
  EXPECT_TRUE(oldRelit.layers.empty());
  EXPECT_EQ(oldRelit.radiance, a.radiance) << "the totals relight the same radiance";

  // Fluoresced parts without the attribute: refused, naming it.
  SpectralImage unsplit = img;
  unsplit.relight.split = false;
  writeSpectralExr(path, unsplit);
  EXPECT_NE(test::errorMessage([&] { readSpectralExr(path); }).find("nxrender.relightDiagonal"),
            std::string::npos);
  std::filesystem::remove(path);
}

// The noise of an image: its squared error against a reference of 16x the samples (less the
// reference's own variance, from its variance channels), relative to each band's mean, pooled
// over the pixels and the bands holding at least 5% of the reference's light, and of those the
// ones where fluoresced light is most of the band when there are such (where the excitation
// draws matter). (The variance channels alone, each pixel's from two replicates, are too
// heavy-tailed for this: their mean moved by 3x in one band between two seeds of a render.)
double relativeNoise(const SpectralImage& img, const SpectralImage& reference) {
  const int nb = reference.bands.count();
  const size_t pixels = reference.sampleCount.size();
  std::vector<double> mean(static_cast<size_t>(nb)), fluoresced(mean.size(), 0.0);
  for (int b = 0; b < nb; ++b) {
    mean[static_cast<size_t>(b)] = imageBand(reference, b).mean;
    for (size_t i = 0; i < pixels; ++i)
      fluoresced[static_cast<size_t>(b)] +=
          reference.layers.at(1).values[i * static_cast<size_t>(nb) + static_cast<size_t>(b)] /
          static_cast<double>(pixels);
  }
  const double brightest = *std::max_element(mean.begin(), mean.end());
  const auto counted = [&](int b, bool onlyFluoresced) {
    const size_t u = static_cast<size_t>(b);
    return mean[u] >= 0.05 * brightest && (!onlyFluoresced || fluoresced[u] > 0.5 * mean[u]);
  };
  bool anyFluoresced = false;
  for (int b = 0; b < nb; ++b) anyFluoresced = anyFluoresced || counted(b, true);
  double sum = 0;
  for (int b = 0; b < nb; ++b) {
    if (!counted(b, anyFluoresced)) continue;
    double squares = 0;
    for (size_t i = 0; i < pixels; ++i) {
      const size_t k = i * static_cast<size_t>(nb) + static_cast<size_t>(b);
      const double d = img.radiance[k] - reference.radiance[k];
      squares += d * d - reference.bandVariance[k];
    }
    sum += squares / static_cast<double>(pixels) /
           (mean[static_cast<size_t>(b)] * mean[static_cast<size_t>(b)]);
  }
  return std::sqrt(std::max(sum, 0.0));
}

// The sphere's dye absorbing over 100 nm (the default 20) around its blue peak: a narrow lamp
// then meets a small part of its absorption.
std::string broadDye(std::string scene) {
  const std::string from = "<stokes>100</stokes>";
  scene.replace(scene.find(from), from.size(), from + "<width>100</width>");
  return scene;
}

// A reference for `lamp`: 1024 samples per pixel, another seed, with its component layers
// (with broadDye).
SpectralImage referenceRender(const std::string& lamp, bool broad = false) {
  RenderOptions o;
  o.seed = 31;
  o.components = true;
  const std::string scene = benchScene(lamp, "", 1024);
  return toSpectralImage(renderText(broad ? broadDye(scene) : scene, o).film);
}

RenderOutput renderTargeted(const std::string& text, const std::vector<std::string>& targets) {
  SceneDesc d = parseScene(text, "t.scn");
  d.relightable = true;
  for (const std::string& t : targets) d.relightTargets.push_back({"", writtenSpectrum(t), t});
  const RenderScene scene = buildRenderScene(d);
  RenderOutput out = render(scene, RenderOptions{});
  EXPECT_EQ(out.stats.relightMissed, 0u);
  return out;
}

// The narrow lamp (430-470 nm) lights the sphere's fluorescence: relit from a render of flat
// excitation most draws miss it; a render told the target draws where it shines. The ratios are
// of noise estimates over 1024 pixels, each from 64 samples: measured 1.0-1.1 with targets and
// about 3 without; the limits leave room for the seeds.
TEST(RelightTargets, NarrowLampRelitNoNoisierThanOneAndAHalfADirectRender) {
  const SpectralImage direct = directRender(broadDye(benchScene(kNarrowLamp)));
  const SpectralImage plain =
      toSpectralImage(renderRelightable(broadDye(benchScene(kLampS1))).film);
  const SpectralImage targeted =
      toSpectralImage(renderTargeted(broadDye(benchScene(kLampS1)), {kNarrowLamp}).film);
  std::vector<std::string> warnings;
  const SpectralImage relitPlain = relightImage(
      plain,
      {groupSpectrum(plain, "lamp", writtenSpectrum(kNarrowLamp), 300, 1100, "narrow", warnings)});
  const SpectralImage relitTargeted =
      relightImage(targeted, {binned(targeted, "lamp", kNarrowLamp)});
  const SpectralImage reference = referenceRender(kNarrowLamp, true);
  const double noise = relativeNoise(direct, reference);
  const double without = relativeNoise(relitPlain, reference) / noise,
               with = relativeNoise(relitTargeted, reference) / noise;
  EXPECT_GT(without, 2.0) << "the case is hard without targets";
  std::printf("narrow lamp: relit %.2f (without targets %.2f) x the direct render's noise\n", with,
              without);
  EXPECT_LE(with, 1.5) << "(without: " << without << ")";
  expectSameBands(relitTargeted, direct, "targeted, relit to its target");
  // Relighting the plain render warned, with its estimate; relighting the targeted one did not
  // (binned checks), and neither does a broad spectrum relit from the plain one.
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("expected about"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("--relight-for lamp=narrow"), std::string::npos) << warnings[0];
  const RelitNoise estimate =
      relitNoiseFactor(plain, {0}, binAverages(writtenSpectrum(kNarrowLamp), plain.relight.grid));
  EXPECT_GE(estimate.factor, kRelitNoiseWarning);
  EXPECT_LT(relitNoiseFactor(plain, {0}, binAverages(writtenSpectrum(kLampS2), plain.relight.grid))
                .factor,
            kRelitNoiseWarning);
  binned(plain, "lamp", kLampS2);
}

// Several targets draw one guided excitation event each: a render told the narrow lamp and the
// broad S2 relit to either is no noisier than 1.5x its direct render.
TEST(RelightTargets, EachOfSeveralTargetsNoNoisierThanOneAndAHalf) {
  const SpectralImage both =
      toSpectralImage(renderTargeted(benchScene(kLampS1), {kNarrowLamp, kLampS2}).film);
  for (const std::string& lamp : {kNarrowLamp, kLampS2}) {
    const SpectralImage direct = directRender(benchScene(lamp));
    const SpectralImage relit = relightImage(both, {binned(both, "lamp", lamp)});
    const SpectralImage reference = referenceRender(lamp);
    const double ratio = relativeNoise(relit, reference) / relativeNoise(direct, reference);
    std::printf("%s: %.2f\n", lamp.c_str(), ratio);
    EXPECT_LE(ratio, 1.5) << lamp;
    expectSameBands(relit, direct, "relit to " + lamp);
  }
  // At most kMaxExcitationGuides targets per group.
  SceneDesc d = parseScene(benchScene(kLampS1), "t.scn");
  d.relightable = true;
  for (int k = 0; k <= kMaxExcitationGuides; ++k)
    d.relightTargets.push_back({"", writtenSpectrum(kLampS2), "S2"});
  EXPECT_NE(test::errorMessage([&] {
              buildRenderScene(d);
            }).find("expected at most 8 targets for a light group"),
            std::string::npos);
}

// Targets move samples only: a targeted render relit to another spectrum is that spectrum's
// direct render (z-tests), and a broad spectrum relit from a plain render does not warn.
TEST(RelightTargets, TargetedRenderRelightsAnySpectrumUnbiased) {
  const SpectralImage targeted =
      toSpectralImage(renderTargeted(benchScene(kLampS1), {kNarrowLamp}).film);
  ASSERT_EQ(targeted.relight.guides.size(), 1u) << "the excitation guides, for the image";
  ASSERT_EQ(targeted.relight.guides[0].size(), 1u);
  const SpectralImage relit = relightImage(targeted, {binned(targeted, "lamp", kLampS2)});
  expectSameBands(relit, directRender(benchScene(kLampS2)), "targeted, relit to S2");
  expectComponentsSum(relit);
}

// A target line narrower than the 0.1 nm grid the mixture is tabulated on, lying between its
// points (450.03-450.07 nm), is integrated at its own knots: the mixture holds it, with the
// integral it has (it once came out 0, and the render lost about 30% of its light), and a
// render targeted at it and at S2 relit to S2 is S2's direct render.
TEST(RelightTargets, ALineBetweenTheGridsPointsIsIntegratedExactly) {
  const std::string line = "<emission scale=\"2e-4\">450.03:0, 450.05:1, 450.07:0</emission>";
  SceneDesc d = parseScene(benchScene(kLampS1), "t.scn");
  d.relightable = true;
  d.relightTargets.push_back({"", writtenSpectrum(line), "line"});
  d.relightTargets.push_back({"", writtenSpectrum(kLampS2), "S2"});
  const RenderScene scene = buildRenderScene(d);
  const Spectrum& mixture = scene.relight.samplingOfSource.at(0);
  // Each target's share is its normalised shape times the mean integral: the line's peak
  // 2e-4 over its integral 2e-4 x 0.04 nm / 2, halved, times the mean of the two integrals.
  const Spectrum lampS2 = writtenSpectrum(kLampS2);
  double s2 = 0;
  for (int k = 0; k < 8000; ++k) {
    const double a = 300 + 0.1 * k;
    s2 += 0.05 * (lampS2(a) + lampS2(a + 0.1));
  }
  const double lineIntegral = 0.5 * 2e-4 * 0.04, mean = (lineIntegral + s2) / 2; // a triangle
  const double expected = (2e-4 / lineIntegral + lampS2(450.05) / s2) / 2 * mean;
  EXPECT_NEAR(mixture(450.05), expected, 1e-3 * expected); // (the written line: its 1e-4 nm grid)
  EXPECT_GT(mixture(450.05), 10 * mixture(450.2));
  RenderOutput out = render(scene, RenderOptions{});
  EXPECT_EQ(out.stats.relightMissed, 0u);
  const SpectralImage targeted = toSpectralImage(out.film);
  const SpectralImage relit = relightImage(targeted, {binned(targeted, "lamp", kLampS2)});
  expectSameBands(relit, directRender(benchScene(kLampS2)), "targeted at a line, relit to S2");
}

// Two lamps of two groups, targets for one of them: the other group's lights keep their own
// spectrum for the choice among lights; a target naming no group of the scene, one that is 0
// everywhere and targets without a relightable build are refused.
TEST(RelightTargets, GroupsAndRefusals) {
  const std::string two = benchScene(kLampS1, kLampS2);
  SceneDesc d = parseScene(two, "t.scn");
  d.relightable = true;
  d.relightTargets.push_back({"lamp", writtenSpectrum(kNarrowLamp), "narrow"});
  const RenderScene scene = buildRenderScene(d);
  ASSERT_EQ(scene.relight.samplingOfSource.size(), 2u);
  EXPECT_DOUBLE_EQ(scene.relight.samplingOfSource[1](600), scene.relight.ofSource[1](600));
  EXPECT_DOUBLE_EQ(scene.relight.samplingOfSource[0](600), 0.0);
  EXPECT_GT(scene.relight.samplingOfSource[0](450), 0.0);

  d.relightTargets = {{"uv", writtenSpectrum(kNarrowLamp), "narrow"}};
  EXPECT_NE(test::errorMessage([&] {
              buildRenderScene(d);
            }).find("expected a light group of the scene (lamp, fill), found 'uv'"),
            std::string::npos);
  d.relightable = false;
  d.relightTargets = {{"", writtenSpectrum(kNarrowLamp), "narrow"}};
  EXPECT_NE(test::errorMessage([&] { buildRenderScene(d); }).find("only with --relightable"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] {
              checkRelightTarget({"", Spectrum(ConstantSpectrum{0}), "zero"}, "--relight-for 0");
            }).find("0 everywhere"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([] {
              relightTargetFromText("lamp=no_such_lamp", "--relight-for");
            }).find("--relight-for lamp=no_such_lamp: expected a CSV file"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([] {
              relightTargetFromText("=D65", "--relight-for");
            }).find("expected GROUP=SPECTRUM"),
            std::string::npos);
  const RelightTargetDesc named = relightTargetFromText("lamp=D65", "--relight-for");
  EXPECT_EQ(named.group, "lamp");
  EXPECT_EQ(named.source, "D65");
}

} // namespace
} // namespace nx
