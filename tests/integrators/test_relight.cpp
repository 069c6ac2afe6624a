// Relightable renders (--relightable) and relighting: a render relit to another lamp spectrum
// equals a direct render under it (z-tests per band), relit to its own spectrum equals itself
// to the grid's bound, a narrow-band render relit to a broad spectrum still holds the whole
// transport, per-light images sum to the total and match the light groups' layers, the
// pattern misses no path of a cascade of dyes, the EXR round trip and the refusals.

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "integrators/relight_image.h"
#include "integrators/relight_pattern.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "io/exr_names.h"
#include "io/exr_write_cost.h"
#include "io/part_merge.h"
#include "io/relight_channels.h"
#include "support/errors.h"
#include "support/part_attributes.h"
#include "support/relight_checks.h"
#include "support/render_checks.h"
#include "support/test_scale.h"

namespace nx {
namespace {

// A render under S1 relit to S2 equals a direct render under S2 in every band (z-test), with
// fluorescence (the sphere re-radiates the lamp's blue into the green); the relit variances
// are those of an estimate as good as the direct render's (within a factor 2 on average).
TEST(Relight, RelitToAnotherLampEqualsADirectRender) {
  const RenderOutput under1 = renderRelightable(benchScene(kLampS1));
  const SpectralImage img = toSpectralImage(under1.film);
  ASSERT_TRUE(img.relight.present());
  ASSERT_EQ(img.relight.sources, std::vector<std::string>{"lamp"});
  const SpectralImage relit = relightImage(img, {binned(img, "lamp", kLampS2)});
  const SpectralImage direct = directRender(benchScene(kLampS2));
  expectSameBands(relit, direct, "S1 relit to S2");
}

// The relit variance channels estimate the relit image's own error: over renders with other
// seeds, the scatter of each relit pixel matches the mean of its variance channel, pooled over
// pixels and bands, with stratified lanes (the default) and with one coordinate per sample's
// lanes. The relit variance is that of the relit replicates (the signed half-differences
// relit), so it holds however the excitation bins' transport is correlated within a replicate.
// Tolerance: the ratio's jackknife standard error over the renders (pooled variances are
// dominated by rare bright samples: with 12 seeds the ratio spread 0.88-1.6 between two sets
// of seeds; 192 seeds give 0.06-0.07), at 3.5 standard errors; the error must be under 0.09,
// so that a variance 1.5x off (bins' variances added as if independent) would fail.
TEST(Relight, RelitVariancesMatchTheScatterOverSeeds) {
  const RenderScene scene = relightableScene(benchScene(kLampS1, "", 8));
  const int kSeeds = test::scaledSamples(192); // trials
  for (const bool stratified : {true, false}) {
    std::vector<std::vector<double>> values, variances;
    for (int seed = 0; seed < kSeeds; ++seed) {
      RenderOptions o;
      o.seed = static_cast<uint32_t>(100 + seed);
      o.stratifiedLanes = stratified;
      const SpectralImage img = toSpectralImage(render(scene, o).film);
      const SpectralImage relit = relightImage(img, {binned(img, "lamp", kLampS2)});
      values.emplace_back(relit.radiance.begin(), relit.radiance.end());
      variances.emplace_back(relit.bandVariance.begin(), relit.bandVariance.end());
    }
    const test::VarianceScatterRatio r = test::varianceScatterRatio(values, variances);
    const char* sampler = stratified ? "stratified" : "sobol";
    EXPECT_LT(r.standardError, test::scaledPower(0.09)) << sampler;
    EXPECT_LT(std::abs(r.ratio - 1), 3.5 * r.standardError)
        << sampler << ": ratio " << r.ratio << " +- " << r.standardError;
  }
}

// Relit to the spectrum it was rendered with, a render is itself to the grid's bound: each
// contribution c S(mu) becomes c S(bin of mu), so per pixel and band |relit - render| <=
// eps * render with eps the largest |S - S_bin| / S_bin within a bin (all contributions >= 0).
// The variances stay the render's.
TEST(Relight, RelitToItsOwnSpectrumIsTheRenderToTheGridBound) {
  for (double step : {5.0, 1.0}) {
    const RenderOutput out = renderRelightable(benchScene(kLampS1, "", 16), step);
    const SpectralImage img = toSpectralImage(out.film);
    const SpectralImage relit = relightImage(img, {}); // every group keeps its spectrum
    const Spectrum s = writtenSpectrum(kLampS1);
    const RelightGrid& grid = img.relight.grid;
    const std::vector<double> avg = binAverages(s, grid);
    double eps = 0;
    for (int j = 0; j < grid.bins; ++j)
      for (int k = 0; k <= 20; ++k) {
        const double v = s(grid.lo(j) + grid.stepNm * k / 20);
        if (avg[static_cast<size_t>(j)] > 0)
          eps = std::max(eps, std::abs(v - avg[static_cast<size_t>(j)]) / avg[j]);
      }
    // (the bound is tight enough to mean something: 4000 K falls steeply into the UV)
    EXPECT_LT(eps, step == 5 ? 0.07 : 0.015);
    double worst = 0;
    for (size_t k = 0; k < img.radiance.size(); ++k) {
      const double r = img.radiance[k], d = std::abs(relit.radiance[k] - r);
      EXPECT_LE(d, eps * r + 1e-6 * r + 1e-12) << k;
      worst = std::max(worst, d / std::max(r, 1e-30));
    }
    EXPECT_GT(worst, 0.0) << "relit to its own spectrum by the bins, not copied";
    for (int b = 0; b < img.bands.count(); ++b) {
      const double ratio = meanVariance(relit, b) / meanVariance(img, b);
      EXPECT_GT(ratio, 0.8) << b;
      EXPECT_LT(ratio, 1.25) << b;
    }
  }
}

// The transport does not depend on the lamp the render used: a lamp black but for 430-470 nm
// relit to a broad spectrum equals a direct render under that (unit spectra are traced; the
// lamp's spectrum is applied per contribution).
TEST(Relight, NarrowBandRenderRelitToABroadSpectrum) {
  const RenderOutput narrow = renderRelightable(benchScene(kNarrowLamp));
  const SpectralImage img = toSpectralImage(narrow.film);
  const SpectralImage relit = relightImage(img, {binned(img, "lamp", kLampS2)});
  // Rendered, the narrow lamp lights the red band only by the far tail of the fluorescence.
  const int red = img.bands.count() - 1;
  EXPECT_LT(imageBand(img, red).mean, 0.1 * imageBand(relit, red).mean);
  const SpectralImage direct = directRender(benchScene(kLampS2));
  expectSameBands(relit, direct, "narrow relit to S2");
}

// Two lamps: relit with one lamp's spectrum at zero, the per-light images sum to the image of
// both (to float rounding), and each is, to the grid's bound, the light group's own layer.
TEST(Relight, PerLightImagesSumToTheTotalAndMatchTheGroupLayers) {
  const std::string fill = "<emission scale=\"2\">400:1, 700:0.5</emission>";
  RenderOptions o;
  o.lightGroups = true;
  const RenderOutput out = renderRelightable(benchScene(kLampS1, fill, 16), 5, o);
  const SpectralImage img = toSpectralImage(out.film);
  ASSERT_EQ(img.relight.sources, (std::vector<std::string>{"lamp", "fill"}));
  const size_t bins = static_cast<size_t>(img.relight.grid.bins);
  const GroupSpectrum darkLamp{"lamp", std::vector<double>(bins, 0.0), "0"};
  const GroupSpectrum darkFill{"fill", std::vector<double>(bins, 0.0), "0"};
  const SpectralImage both = relightImage(img, {});
  const SpectralImage fillOnly = relightImage(img, {darkLamp});
  const SpectralImage lampOnly = relightImage(img, {darkFill});
  const int nb = img.bands.count();
  ASSERT_EQ(img.layers.size(), 2u);
  for (size_t k = 0; k < both.radiance.size(); ++k) {
    const double sum = lampOnly.radiance[k] + fillOnly.radiance[k];
    EXPECT_NEAR(sum, both.radiance[k], 1e-5 * both.radiance[k] + 1e-12) << k;
    // light.lamp and light.fill: the rendered split (blackbody and a linear ramp, both
    // within 3% over a 5 nm bin)
    EXPECT_NEAR(lampOnly.radiance[k], img.layers[0].values[k], 0.03 * img.layers[0].values[k])
        << k / static_cast<size_t>(nb);
    EXPECT_NEAR(fillOnly.radiance[k], img.layers[1].values[k], 0.03 * img.layers[1].values[k]);
  }
}

// A cascade of dyes (UV -> blue by the walls, blue -> red by a ball) and several sensors: the
// pattern holds every contribution (none dropped), and under a lamp with light only below 370
// nm the relit red is what the cascade brings (a render of the same says so too).
TEST(Relight, PatternHoldsCascadesOfDyesForAnySensor) {
  const std::string room =
      "<scene><settings><xres>16</xres><yres>16</yres><mode>spectral_mcpt</mode><depth>6</depth>"
      "<sampl>16</sampl></settings><camera><position>0,0,0</position><look_at>0,0,1</look_at>"
      "<fov>60</fov></camera><sphere><center>0,0,0</center><radius>4</radius><material>matte</"
      "material><reflectance>0.3</reflectance><fluorescence><absorption>350</absorption><stokes>"
      "100</stokes></fluorescence></sphere><sphere><center>0.8,0,2.5</center><radius>0.6</"
      "radius><material>matte</material><reflectance>0.2</reflectance><fluorescence><absorption>"
      "450</absorption><stokes>160</stokes></fluorescence></sphere><sphere group=\"uv\"><center>"
      "-0.8,0.5,2</center><radius>0.3</radius><material>matte</material><reflectance>0</"
      "reflectance><emission>330:0, 340:20, 365:20, 370:0</emission></sphere></scene>";
  for (const char* sensor : {"400:700:20", "gaussian:420,500,610@30", "boxes:430-450,600-650"}) {
    RenderOptions o;
    o.bands = Sensor::parse(sensor, "test");
    const RenderOutput out = renderRelightable(room, 5, o); // checks relightMissed == 0
    const SpectralImage img = toSpectralImage(out.film);
    const int red = img.bands.count() - 1; // the longest band: only the cascade reaches it
    EXPECT_GT(imageBand(img, red).mean, 0.0) << sensor;
    // Relit to its own spectrum: the lamp's ramps make the grid's per-sample bound loose here,
    // but the excitation is uniform within each 5 nm bin, so each pixel's difference from the
    // render has mean 0 (a paired z-test over the pixels).
    expectSameBands(relightImage(img, {}), img, sensor);
  }
}

// Light groups of the longest name whose channels OpenEXR stores whole: two such names
// differing in their last byte keep two layers and two transports through the file, at the
// longest wavelength text (two 250-byte names wrote 4 light channels instead of 124 and the
// transport collapsed); a name one byte longer is refused at its line, and the writer refuses
// any name OpenEXR would cut.
TEST(Relight, LongestGroupNamesKeepTheirChannels) {
  const size_t n = longestLightGroupName();
  EXPECT_EQ(longestExrNameOfLightGroup(std::string(n, 'g')), kMaxExrNameBytes);
  const std::string a = std::string(n - 1, 'g') + "a", b = std::string(n - 1, 'g') + "b";
  std::string text = benchScene(kLampS1, kLampS1, 1, "1000:1090:10");
  text.replace(text.find("group=\"lamp\""), 12, "group=\"" + a + "\"");
  text.replace(text.find("group=\"fill\""), 12, "group=\"" + b + "\"");
  RenderOptions o;
  o.lightGroups = true;
  const SpectralImage img = toSpectralImage(renderRelightable(text, 5, o).film);
  ASSERT_EQ(img.relight.sources, (std::vector<std::string>{a, b}));
  const std::string path =
      (std::filesystem::temp_directory_path() / "nx_relight_long_groups.exr").string();
  writeSpectralExr(path, img);
  {
    // Every channel is there: as many as the image's shape says (the memory check counts them).
    Imf::InputFile in(path.c_str());
    size_t channels = 0;
    for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it)
      ++channels;
    EXPECT_EQ(channels, exrChannelCount(shapeOf(img)));
    EXPECT_GT(channels, 2 * 2 * img.relight.entries.size());
  }
  const SpectralImage back = readSpectralExr(path);
  std::filesystem::remove(path);
  EXPECT_EQ(back.relight.sources, img.relight.sources);
  EXPECT_EQ(back.relight.entries.size(), img.relight.entries.size());
  EXPECT_EQ(back.relight.values, img.relight.values);
  ASSERT_EQ(back.layers.size(), img.layers.size());
  for (size_t k = 0; k < img.layers.size(); ++k) {
    EXPECT_EQ(back.layers[k].name, img.layers[k].name);
    EXPECT_EQ(back.layers[k].values, img.layers[k].values) << img.layers[k].name;
    EXPECT_EQ(back.layers[k].variances, img.layers[k].variances) << img.layers[k].name;
  }
  // One byte more: refused at the emitter's line, before anything is rendered.
  std::string longer = text;
  longer.replace(longer.find(a), a.size(), a + "x");
  EXPECT_EQ(test::errorMessage([&] { (void)parseScene(longer, "t.scn"); }),
            "t.scn:1: expected a light group name of at most " + std::to_string(n) +
                " bytes in group=\"...\" (its EXR channel names, up to " +
                std::to_string(kMaxExrNameBytes - n) +
                " bytes longer, must fit OpenEXR's 255), found one of " + std::to_string(n + 1) +
                " bytes");
  // The writer's own check, for names that do not come from a scene (Python's attributes).
  SpectralImage tagged = img;
  tagged.attributes[std::string(256, 'k')] = "v";
  const std::string m = test::errorMessage([&] { writeSpectralExr(path, tagged); });
  EXPECT_EQ(m.substr(0, m.find(": 'kkk")),
            path + ": expected attribute names of 1-255 bytes (what OpenEXR stores), found one of "
                   "256 bytes");
  EXPECT_FALSE(std::filesystem::exists(path));
}

// An image written and read back relights as the image in memory; a file without a transport
// and a group it does not hold are refused.
TEST(Relight, ExrRoundTripAndRefusals) {
  const RenderOutput out = renderRelightable(benchScene(kLampS1, "", 4));
  const SpectralImage img = toSpectralImage(out.film);
  const std::string path =
      (std::filesystem::temp_directory_path() / "nx_relight_roundtrip.exr").string();
  writeSpectralExr(path, img);
  const SpectralImage back = readSpectralExr(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(back.relight.present());
  EXPECT_EQ(back.relight.entries.size(), img.relight.entries.size());
  EXPECT_EQ(back.relight.values, img.relight.values);
  EXPECT_EQ(back.relight.halfDifferences, img.relight.halfDifferences);
  const GroupSpectrum s2 = binned(img, "lamp", kLampS2);
  EXPECT_EQ(relightImage(back, {s2}).radiance, relightImage(img, {s2}).radiance);
  EXPECT_EQ(test::errorMessage([&] {
              relightImage(back, {s2, s2});
            }),
            "expected each light group once, found 'lamp' twice");
  std::vector<std::string> warnings;
  EXPECT_EQ(test::errorMessage([&] {
              groupSpectrum(img, "sky", writtenSpectrum(kLampS2), 300, 1100, "x", warnings);
            }),
            "expected a light group of the image (lamp), found 'sky'");
  // A table that ends inside the reach of the transport: 0 beyond it, with a warning.
  groupSpectrum(img, "lamp", writtenSpectrum(kLampS2), 380, 800, "led.csv", warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("led.csv: warning: tabulated over 380-800 nm and the transport of "
                             "light group 'lamp' reaches 3"),
            std::string::npos)
      << warnings[0];
  const SpectralImage plain = toSpectralImage(renderText(benchScene(kLampS1, "", 2)).film);
  EXPECT_EQ(test::errorMessage([&] { relightImage(plain, {}); }),
            "expected a relightable image (rendered with --relightable), found one without "
            "relight channels");
}

// Farm parts of a relightable render: crops merge into the whole transport bit for bit, sample
// ranges into its sample-weighted mean (the half-differences likewise); a part without a
// transport, and band ranges, are refused.
TEST(Relight, PartsMergeLikeTheBands) {
  const RenderScene scene = relightableScene(benchScene(kLampS1, "", 4));
  auto part = [&](const std::string& name, std::optional<PixelRect> crop, int first, int count) {
    RenderOptions o;
    o.crop = crop;
    o.firstSample = first;
    o.samples = count;
    SpectralImage img = toSpectralImage(render(scene, o).film);
    test::setPartAttributes(img, 0, first, count);
    return ImagePart{name, img};
  };
  const SpectralImage whole = part("whole", std::nullopt, 0, 4).image;
  const SpectralImage crops = mergeParts(
      {part("top", PixelRect{0, 0, 32, 13}, 0, 4), part("bottom", PixelRect{0, 13, 32, 32}, 0, 4)});
  ASSERT_TRUE(crops.relight.present());
  EXPECT_EQ(crops.relight.values, whole.relight.values);
  EXPECT_EQ(crops.relight.halfDifferences, whole.relight.halfDifferences);
  const SpectralImage ranges =
      mergeParts({part("r1", std::nullopt, 0, 2), part("r2", std::nullopt, 2, 2)});
  ASSERT_EQ(ranges.relight.values.size(), whole.relight.values.size());
  for (size_t k = 0; k < whole.relight.values.size(); ++k)
    ASSERT_NEAR(ranges.relight.values[k], whole.relight.values[k],
                1e-5f * std::abs(whole.relight.values[k]) + 1e-12f)
        << k;
  // The relit merge is the relit whole (to float rounding).
  const GroupSpectrum s2 = binned(whole, "lamp", kLampS2);
  const SpectralImage a = relightImage(ranges, {s2}), b = relightImage(whole, {s2});
  for (size_t k = 0; k < a.radiance.size(); ++k)
    ASSERT_NEAR(a.radiance[k], b.radiance[k], 1e-4f * b.radiance[k] + 1e-12f);
  ImagePart plain{"plain", toSpectralImage(renderText(benchScene(kLampS1, "", 2)).film)};
  plain.image.attributes = part("r2", std::nullopt, 2, 2).image.attributes;
  EXPECT_EQ(test::errorMessage([&] {
              mergeParts({part("r1", std::nullopt, 0, 2), plain});
            }),
            "plain: does not belong with r1: their relight transports differ (none against 1 "
            "groups, " +
                std::to_string(whole.relight.entries.size()) +
                " entries; render every part with the same --relightable, --relight-step and "
                "--relight-for)");
  // Band ranges of a relightable render do not stitch (the pattern is the bands').
  auto bandsPart = [&](const std::string& name, const char* bands) {
    RenderOptions o;
    o.samples = 1;
    o.bands = Sensor::parse(bands, "test");
    SpectralImage img = toSpectralImage(render(scene, o).film);
    img.attributes = whole.attributes;
    img.attributes["nxrender.renderKey"] = "key";
    img.attributes["nxrender.seed"] = "0";
    img.attributes["nxrender.sampleRange"] = "0:1";
    img.attributes["nxrender.bands"] = img.bands.toString();
    return ImagePart{name, img};
  };
  EXPECT_EQ(test::errorMessage([&] {
              mergeParts({bandsPart("blue", "400:500:20"), bandsPart("red", "520:700:20")});
            }),
            "blue: a relightable render's band ranges cannot be stitched (its transport's "
            "pattern is the bands'): render the bands together, split by --crop or --spp-range "
            "instead");
}

// One light group with emitters of two spectra (here ungrouped: the group "default", as a lamp
// and a sky often are): each spectrum is a source of its own ("default", "default.2"), relit
// together when the group is given a new spectrum, each with its own when it is not. The same
// spectrum at another scale is the same source.
TEST(Relight, GroupsWithSeveralSpectraRelightAsOne) {
  auto ungrouped = [](std::string text) {
    for (size_t at; (at = text.find(" group=\"")) != std::string::npos;)
      text.erase(at, text.find('"', at + 8) + 1 - at);
    return text;
  };
  const std::string fillS1 = "<emission scale=\"3e-4\">blackbody:4000</emission>";
  EXPECT_EQ(relightableScene(ungrouped(benchScene(kLampS1, fillS1))).relight.ofSource.size(), 1u);
  const std::string fillFlat = "<emission scale=\"2e-4\">1</emission>";
  const std::string fillS2 =
      "<emission scale=\"2e-4\">380:0.2, 450:3, 500:0.5, 560:2, 650:1, 800:0.1</emission>";
  const RenderOutput out = renderRelightable(ungrouped(benchScene(kLampS1, fillFlat)));
  const SpectralImage img = toSpectralImage(out.film);
  EXPECT_EQ(img.relight.sources, (std::vector<std::string>{"default", "default.2"}));
  EXPECT_EQ(img.relight.groups(), std::vector<std::string>{"default"});
  // Both emitters relit to S2 (the fill's factor 2e-4 applying) against a direct render.
  expectSameBands(relightImage(img, {binned(img, "default", kLampS2)}),
                  directRender(ungrouped(benchScene(kLampS2, fillS2))), "default relit to S2");
  // Without a new spectrum each source keeps its own: the render, to the grid's bound.
  const SpectralImage own = relightImage(img, {});
  for (size_t k = 0; k < img.radiance.size(); ++k)
    ASSERT_NEAR(own.radiance[k], img.radiance[k], 0.07 * img.radiance[k] + 1e-12) << k;
  // A written file keeps the sources apart (one's name is a prefix of the other's).
  const std::string path =
      (std::filesystem::temp_directory_path() / "nx_relight_sources.exr").string();
  writeSpectralExr(path, img);
  const SpectralImage back = readSpectralExr(path);
  std::filesystem::remove(path);
  EXPECT_EQ(back.relight.sources, img.relight.sources);
  EXPECT_EQ(back.relight.values, img.relight.values);
}

// A file's transport that is not what nxrender writes is refused, naming the file and what was
// expected: the grid, a source's spectrum, a channel's band or bin, a missing half-difference.
TEST(Relight, MalformedTransportChannelsAreRefused) {
  const std::vector<std::string> bands = {"400,000000nm", "420,000000nm"};
  const std::string t = "relight.lamp.T.402,500000nm.400,000000nm";
  auto parse = [&](std::map<std::string, std::string> attributes,
                   std::vector<std::string> channels) {
    RelightLayers rl;
    return test::errorMessage(
        [&] { parseRelightChannels(attributes, channels, bands, "f.exr", rl); });
  };
  std::string flat;
  for (int j = 0; j < 160; ++j) flat += j ? ",1" : "1";
  const std::map<std::string, std::string> good = {{"nxrender.relightSources", "lamp"},
                                                   {"nxrender.relightGrid", "300:1100:5"},
                                                   {"nxrender.relightSpectrum.lamp", flat}};
  EXPECT_EQ(parse(good, {t, "HalfDifference." + t}), "no error");
  auto with = [&](const std::string& key, const std::string& value) {
    auto a = good;
    if (value.empty())
      a.erase(key);
    else
      a[key] = value;
    return a;
  };
  EXPECT_EQ(parse(with("nxrender.relightGrid", ""), {t}),
            "f.exr: expected the attribute nxrender.relightGrid beside nxrender.relightSources, "
            "found none");
  EXPECT_EQ(
      parse(with("nxrender.relightGrid", "300:1100:3"), {t}),
      "f.exr: nxrender.relightGrid: expected a step in nm from 0.1 to 100 that divides 5 (0.1, "
      "0.25, 0.5, 1, 2.5, 5) or is a multiple of 5 (its bins nest with the 5 nm re-radiation "
      "grid), found 3");
  EXPECT_EQ(parse(with("nxrender.relightSpectrum.lamp", "1,2"), {t}),
            "f.exr: expected 160 values in nxrender.relightSpectrum.lamp (one per bin), found 2");
  EXPECT_EQ(parse(good, {"relight.lamp.T.402,500000nm.410,000000nm"}),
            "f.exr: expected a band of the image in the channel "
            "relight.lamp.T.402,500000nm.410,000000nm, found 410,000000nm");
  EXPECT_EQ(parse(good, {"relight.lamp.T.403,000000nm.400,000000nm"}),
            "f.exr: expected an excitation bin centre of the grid in the channel "
            "relight.lamp.T.403,000000nm.400,000000nm, found 403,000000nm");
  EXPECT_EQ(parse(good, {t}), "f.exr: expected a channel HalfDifference." + t + ", found none");
  EXPECT_EQ(parse(good, {"relight.sky.T.402,500000nm.400,000000nm"}),
            "f.exr: expected relight channels of the sources nxrender.relightSources lists, found "
            "relight.sky.T.402,500000nm.400,000000nm");
}

// Every spectrum and transport value that enters a relight passes the scene's checks: a new
// spectrum beyond the 1e12 emission limit or a blackbody the limit refuses (they overflowed
// only at the write, or came back to Python as inf), a tampered file's negative or 3e38
// transport values and its rendered spectra beyond the limit (relit silently), and a relit
// image a float cannot hold, each named by its group, key, channel or pixel.
TEST(Relight, SpectraAndTransportAreCheckedLikeAScenes) {
  const SpectralImage img = toSpectralImage(renderRelightable(benchScene(kLampS1, "", 2)).film);
  std::vector<std::string> warnings;
  EXPECT_EQ(test::errorMessage([&] {
              groupSpectrum(img, "lamp", Spectrum(ConstantSpectrum{2e12}), 300, 1100,
                            "lights['lamp']", warnings);
            }).substr(0, 50),
            "lights['lamp']: expected an emission within [0, 1e");
  EXPECT_NE(test::errorMessage([&] {
              groupSpectrumFromText(img, "lamp", "blackbody:100", warnings);
            }).find("blackbody:100: expected an emission within [0, 1e+12]"),
            std::string::npos);
  const std::string csv = ::testing::TempDir() + "/bright_lamp.csv";
  std::ofstream(csv) << "nm,value\n300,1\n700,5e12\n1100,1\n";
  EXPECT_NE(test::errorMessage([&] {
              groupSpectrumFromText(img, "lamp", csv, warnings);
            }).find("found 5e+12 at 700 nm"),
            std::string::npos);
  // A tampered file: each value read back is checked, naming what holds it.
  const std::string path =
      (std::filesystem::temp_directory_path() / "nx_relight_tampered.exr").string();
  auto readError = [&](const std::function<void(SpectralImage&)>& tamper) {
    SpectralImage t = img;
    tamper(t);
    writeSpectralExr(path, t);
    const std::string m = test::errorMessage([&] { (void)readSpectralExr(path); });
    std::filesystem::remove(path);
    return m;
  };
  const std::string first = relightChannelName(img.relight, 0, 0, [&] {
    std::vector<std::string> names;
    for (int b = 0; b < img.bands.count(); ++b)
      names.push_back(spectralChannelName(img.bands.channelNm(b)).substr(3));
    return names;
  }());
  EXPECT_EQ(readError([](SpectralImage& t) { t.relight.values[5] = -1; }),
            path + ": channel " + first +
                ": expected transport values within [0, 3.4e+26] (what an emission at the 1e12 "
                "limit relights into a float), found -1 at pixel 5,0");
  EXPECT_NE(readError([](SpectralImage& t) { t.relight.values[0] = 3e38f; }).find("found 3e+38"),
            std::string::npos);
  EXPECT_NE(readError([](SpectralImage& t) {
              t.relight.halfDifferences[0] = -3e38f;
            }).find(": expected half-differences within +-3.4e+26"),
            std::string::npos);
  EXPECT_EQ(readError([](SpectralImage& t) { t.relight.spectra[0][3] = 2e12; }),
            path + ": nxrender.relightSpectrum.lamp: expected bin averages of an emission within "
                   "[0, 1e+12], found 2e+12");
  // Within every bound, a relit image can still pass a float: refused, naming the pixel.
  SpectralImage big = img;
  for (float& v : big.relight.values) v = 3e26f;
  GroupSpectrum bright{"lamp",
                       std::vector<double>(static_cast<size_t>(big.relight.grid.bins), 1e12),
                       "blackbody:3000"};
  const std::string m = test::errorMessage([&] { relightImage(big, {bright}); });
  EXPECT_EQ(m.substr(0, m.find(" in band")),
            "expected a relit image whose values and variances a float holds (3.4e38), found an "
            "overflow at pixel 0,0");
  EXPECT_NE(m.find("relit with lamp=blackbody:3000"), std::string::npos) << m;
}

// What a relightable build cannot relight is refused by name: emitting media, environment
// maps, other modes; a resume; a step off the grid.
TEST(Relight, RefusalsNameWhatCannotBeRelit) {
  const std::string medium =
      "<scene><settings><xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode></settings><camera>"
      "<position>0,0,-4</position><look_at>0,0,0</look_at></camera><sphere><center>0,0,0</"
      "center><radius>1</radius><material>interface</material><medium><sigma_a>1</sigma_a>"
      "<sigma_s>0</sigma_s><emission>1</emission></medium></sphere></scene>";
  EXPECT_NE(test::errorMessage([&] {
              relightableScene(medium);
            }).find("--relightable: expected media that do not emit, found an emitting medium"),
            std::string::npos);
  std::string rt = benchScene(kLampS1);
  rt.replace(rt.find("spectral_mcpt"), 13, "mcpt");
  EXPECT_EQ(test::errorMessage([&] { relightableScene(rt); }),
            "t.scn: --relightable: expected a spectral_mcpt scene (relighting replaces emission "
            "spectra), found mode mcpt");
  const RenderScene scene = relightableScene(benchScene(kLampS1, "", 2));
  RenderOptions o;
  o.relightStepNm = 3;
  EXPECT_EQ(test::errorMessage([&] { render(scene, o); }),
            "--relight-step: expected a step in nm from 0.1 to 100 that divides 5 (0.1, 0.25, 0.5, "
            "1, 2.5, 5) or is a multiple of 5 (its bins nest with the 5 nm re-radiation grid), "
            "found 3");
  for (const double fine : {1e-6, 1e-300, 0.05}) {
    o.relightStepNm = fine;
    EXPECT_NE(test::errorMessage([&] { render(scene, o); }).find("expected a step in nm from 0.1"),
              std::string::npos)
        << fine;
  }
  const Film stored = render(scene, {}).film;
  RenderOptions resume;
  resume.resumeFrom = &stored;
  EXPECT_EQ(test::errorMessage([&] { render(scene, resume); }),
            "--relightable: continuing a relightable render (--resume) is not supported; render "
            "it again, or split it by --spp-range parts and merge them");
}

// A stop raised while a render is being prepared (the sources' spectra, the pattern, the light
// sampler: minutes for a fine grid before its step was bounded) ends it before its first
// sample, with nothing rendered; raised later, the render stops between samples as before.
TEST(Relight, StopWhilePreparingEndsBeforeRendering) {
  const RenderScene scene = relightableScene(benchScene(kLampS1, kLampS2, 2));
  std::atomic<bool> stop{true};
  RenderOptions o;
  o.stop = &stop;
  EXPECT_THROW(render(scene, o), StoppedBeforeRendering);
  o.relightStepNm = 0.1;
  EXPECT_THROW(render(scene, o), StoppedBeforeRendering);
  stop = false;
  EXPECT_FALSE(render(scene, o).stats.stopped);
}

} // namespace
} // namespace nx
