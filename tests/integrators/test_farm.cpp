#include <gtest/gtest.h>

#include "core/error.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "io/part_merge.h"
#include "support/errors.h"

namespace nx {
namespace {

const char* kScene =
    "<scene><settings><xres>40</xres><yres>30</yres><mode>spectral_mcpt</mode><depth>4</"
    "depth><sampl>6</sampl>"
    "</settings><camera><position>0,2,-6</position><look_at>0,1,0</look_at></camera>"
    "<plane><normal>0,1,0</normal><distance>0</distance><material>matte</"
    "material><reflectance>0.5</reflectance></plane>"
    "<sphere><center>0,1,0</center><radius>1</radius><material>glass</material></sphere>"
    "<sphere><center>1.5,3,-1</center><radius>0.5</radius><material>matte</material><emission>5</"
    "emission></sphere>"
    "</scene>";

const RenderScene& scene() {
  static const RenderScene s = buildRenderScene(parseScene(kScene, "farm.scn"));
  return s;
}

// A part rendered with `o` for samples [first, first + count) of `crop`, with the attributes
// nxrender writes for merging.
ImagePart renderedPart(const std::string& name, RenderOptions o, std::optional<PixelRect> crop,
                       int first, int count, bool geometryAovs = false) {
  o.crop = crop;
  o.firstSample = first;
  o.samples = count;
  SpectralImage img = toSpectralImage(render(scene(), o).film);
  if (geometryAovs) addGeometryAovs(scene(), img);
  img.attributes["nxrender.sampler"] = o.stratifiedLanes ? "stratified" : "sobol";
  img.attributes["nxrender.renderKey"] = "key";
  img.attributes["nxrender.seed"] = "0";
  img.attributes["nxrender.bands"] = img.bands.toString();
  img.attributes["nxrender.sampleRange"] =
      std::to_string(first) + ":" + std::to_string(first + count);
  return {name, img};
}

ImagePart part(const std::string& name, std::optional<PixelRect> crop, int first, int count) {
  ImagePart p = renderedPart(name, {}, crop, first, count);
  p.image.attributes["nxrender.renderSeconds"] = std::to_string(0.25 + count);
  p.image.attributes["nxrender.estimatedRelativeError"] = "0.5";
  return p;
}

// Crops merge into exactly the full render, bit for bit.
TEST(Farm, CropsMergeBitIdentical) {
  const SpectralImage full = part("full", std::nullopt, 0, 6).image;
  const SpectralImage merged =
      mergeParts({part("a", PixelRect{0, 0, 40, 7}, 0, 6), part("b", PixelRect{0, 7, 17, 30}, 0, 6),
                  part("c", PixelRect{17, 7, 40, 30}, 0, 6)});
  EXPECT_EQ(merged.radiance, full.radiance);
  EXPECT_EQ(merged.xyz, full.xyz);
  EXPECT_EQ(merged.rgb, full.rgb);
  EXPECT_EQ(merged.sampleCount, full.sampleCount);
  EXPECT_EQ(merged.attributes.at("nxrender.sampleRange"), "0:6");
}

// Sample ranges merge into the full render up to the float rounding of the parts' means.
TEST(Farm, SampleRangesMergeUpToRounding) {
  const SpectralImage full = part("full", std::nullopt, 0, 6).image;
  const SpectralImage merged =
      mergeParts({part("r1", std::nullopt, 0, 2), part("r2", std::nullopt, 2, 6 - 2)});
  ASSERT_EQ(merged.radiance.size(), full.radiance.size());
  for (size_t i = 0; i < full.radiance.size(); ++i)
    EXPECT_NEAR(merged.radiance[i], full.radiance[i],
                4e-7 * std::max(1.0f, std::abs(full.radiance[i])));
  EXPECT_EQ(merged.sampleCount, full.sampleCount);
  // The merged time is the parts' times added (0.25 + 2 and 0.25 + 4), not the first part's.
  EXPECT_DOUBLE_EQ(std::stod(merged.attributes.at("nxrender.renderSeconds")), 6.5);
  // The merged error estimate describes the merged image, not the first part.
  double y = 0, v = 0;
  for (size_t i = 0; i < merged.yVariance.size(); ++i)
    v += merged.yVariance[i], y += merged.xyz[3 * i + 1];
  const double n = static_cast<double>(merged.yVariance.size());
  EXPECT_NEAR(std::stod(merged.attributes.at("nxrender.estimatedRelativeError")),
              std::sqrt(v / n) / (y / n), 1e-5);
  // The merged error estimate (sum of (n_k / N)^2 var_k) agrees with the full render's.
  double fullVar = 0, mergedVar = 0;
  for (size_t i = 0; i < full.yVariance.size(); ++i)
    fullVar += full.yVariance[i], mergedVar += merged.yVariance[i];
  EXPECT_GT(mergedVar, 0.6 * fullVar);
  EXPECT_LT(mergedVar, 1.6 * fullVar);
  // Any mix: a crop of one range with the whole image of another.
  const SpectralImage mixed = mergeParts({part("top", PixelRect{0, 0, 40, 15}, 0, 2),
                                          part("bottom", PixelRect{0, 15, 40, 30}, 0, 2),
                                          part("rest", std::nullopt, 2, 4)});
  for (size_t i = 0; i < full.radiance.size(); ++i)
    EXPECT_NEAR(mixed.radiance[i], full.radiance[i],
                4e-7 * std::max(1.0f, std::abs(full.radiance[i])));
  // Each pixel's samples split differently: crop A whole (0:6) beside crop B as 0:2 + 2:6
  // (refused before: the pixels' range sets differed although every pixel holds 0:6).
  const SpectralImage split = mergeParts({part("A", PixelRect{0, 0, 40, 15}, 0, 6),
                                          part("B1", PixelRect{0, 15, 40, 30}, 0, 2),
                                          part("B2", PixelRect{0, 15, 40, 30}, 2, 4)});
  EXPECT_EQ(split.attributes.at("nxrender.sampleRange"), "0:6");
  for (size_t i = 0; i < full.radiance.size(); ++i)
    EXPECT_NEAR(split.radiance[i], full.radiance[i],
                4e-7 * std::max(1.0f, std::abs(full.radiance[i])));
  // Holes in a pixel's set are still refused: 0:2 + 4:6 beside 0:6 (fewer samples), and
  // 0:2 + 4:8 beside 0:6 (as many samples, other ones).
  EXPECT_NE(test::errorMessage([] {
              mergeParts({part("A", PixelRect{0, 0, 40, 15}, 0, 6),
                          part("B1", PixelRect{0, 15, 40, 30}, 0, 2),
                          part("B2", PixelRect{0, 15, 40, 30}, 4, 2)});
            }).find("missing region"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([] {
              mergeParts({part("A", PixelRect{0, 0, 40, 15}, 0, 6),
                          part("B1", PixelRect{0, 15, 40, 30}, 0, 2),
                          part("B2", PixelRect{0, 15, 40, 30}, 4, 4)});
            }).find("parts cover different sample ranges in different pixels"),
            std::string::npos);
}

std::string mergeError(std::vector<ImagePart> parts) {
  return test::errorMessage([&] { mergeParts(parts); });
}

TEST(Farm, RefusesPartsThatDoNotBelongTogether) {
  const ImagePart a = part("a.exr", PixelRect{0, 0, 40, 15}, 0, 2),
                  b = part("b.exr", PixelRect{0, 15, 40, 30}, 0, 2);
  ImagePart other = b;
  other.image.attributes["nxrender.renderKey"] = "another";
  EXPECT_EQ(mergeError({a, other})
                .rfind("b.exr: does not belong with a.exr: its nxrender.renderKey is 'another'", 0),
            0u);
  // A part of the earlier default sampler beside one of today's: named by the sampler (the
  // render keys differ too, but would not say why).
  RenderOptions sobolLanes;
  sobolLanes.stratifiedLanes = false;
  const ImagePart sobol = renderedPart("b.exr", sobolLanes, PixelRect{0, 15, 40, 30}, 0, 2);
  EXPECT_EQ(mergeError({a, sobol}),
            "b.exr: does not belong with a.exr: its nxrender.sampler is 'sobol', not 'stratified'");
  ImagePart seed = b;
  seed.image.attributes["nxrender.seed"] = "7";
  EXPECT_EQ(mergeError({a, seed}),
            "b.exr: does not belong with a.exr: its nxrender.seed is '7', not '0'");
  // Other bands: merged as a separate band set, whose crops must cover the image.
  ImagePart bands = b;
  bands.image.attributes["nxrender.bands"] = "400:700:20";
  EXPECT_EQ(mergeError({a, bands}),
            "the parts with bands 31 box bands responding over 395-705 nm (a.exr): missing "
            "region: 600 pixels within 0,15,40,30 have fewer than the 2 samples of the others (a "
            "part is missing)");
  ImagePart size = b;
  size.image.fullWidth = 80;
  EXPECT_EQ(mergeError({a, size}),
            "b.exr: does not belong with a.exr: its image is 80x30, not 40x30");
  const ImagePart overlapping = part("c.exr", PixelRect{0, 10, 40, 20}, 0, 2);
  EXPECT_EQ(mergeError({a, b, overlapping}),
            "c.exr: overlaps a.exr: pixels 0,10,40,15 with samples 0:2 and 0:2");
  const ImagePart repeated = part("d.exr", std::nullopt, 1, 2);
  EXPECT_EQ(mergeError({a, b, repeated}),
            "d.exr: overlaps a.exr: pixels 0,0,40,15 with samples 1:3 and 0:2");
  EXPECT_EQ(mergeError({a}),
            "missing region: 600 pixels within 0,15,40,30 have fewer than the 2 samples of the "
            "others (a part is missing)");
  EXPECT_EQ(mergeError({a, b, part("e.exr", PixelRect{0, 0, 20, 30}, 2, 2)}),
            "missing region: 600 pixels within 20,0,40,30 have fewer than the 4 samples of the "
            "others (a part is missing)");
  ImagePart interrupted = b;
  interrupted.image.sampleCount[5] = 1;
  EXPECT_EQ(
      mergeError({a, interrupted})
          .rfind("b.exr: holds 1 samples in some pixels instead of the 2 of its range 0:2", 0),
      0u);
  EXPECT_EQ(mergeError({}), "nothing to merge");
}

ImagePart bandPart(const std::string& name, const char* bands, std::optional<PixelRect> crop,
                   int first, int count) {
  RenderOptions o;
  o.bands = Sensor::parse(bands);
  return renderedPart(name, o, crop, first, count);
}

// Renders of disjoint band ranges (each possibly split into crops) stitch into one image with
// every band in wavelength order, each band bit for bit its render's; overlapping bands,
// other samples and mixed kinds of bands are refused.
TEST(Farm, DisjointBandRangesStitch) {
  const ImagePart nir = bandPart("nir.exr", "710:1000:10", std::nullopt, 0, 2);
  const ImagePart vis = bandPart("vis.exr", "400:700:10", std::nullopt, 0, 2);
  const ImagePart visTop = bandPart("top.exr", "400:700:10", PixelRect{0, 0, 40, 12}, 0, 2),
                  visBottom = bandPart("bottom.exr", "400:700:10", PixelRect{0, 12, 40, 30}, 0, 2);
  const SpectralImage s = mergeParts({nir, visTop, visBottom});
  ASSERT_EQ(s.bands.count(), 31 + 30);
  for (int b = 1; b < s.bands.count(); ++b) EXPECT_LT(s.bands.centroid(b - 1), s.bands.centroid(b));
  EXPECT_DOUBLE_EQ(s.bands.centroid(0), 400);
  EXPECT_DOUBLE_EQ(s.bands.centroid(60), 1000);
  EXPECT_EQ(Sensor::parse(s.attributes.at("nxrender.bands")).count(), 61);
  const size_t pixels = 40 * 30;
  for (size_t i = 0; i < pixels; ++i) {
    for (int b = 0; b < 31; ++b)
      ASSERT_EQ(s.radiance[i * 61 + b], vis.image.radiance[i * 31 + b]) << i << " " << b;
    for (int b = 0; b < 30; ++b)
      ASSERT_EQ(s.radiance[i * 61 + 31 + b], nir.image.radiance[i * 30 + b]) << i << " " << b;
  }
  EXPECT_EQ(s.xyz, nir.image.xyz); // the first set's colour channels
  EXPECT_EQ(s.sampleCount, vis.image.sampleCount);
  EXPECT_EQ(mergeError({vis, bandPart("more.exr", "690:1000:10", std::nullopt, 0, 2)}),
            "more.exr: cannot be stitched with vis.exr: both hold the band S0.690,000000nm "
            "(stitch renders of disjoint bands)");
  EXPECT_EQ(mergeError({vis, bandPart("later.exr", "710:1000:10", std::nullopt, 2, 2)}),
            "later.exr: cannot be stitched with vis.exr (other bands): its nxrender.sampleRange "
            "is '2:4', not '0:2' (band ranges are stitched from renders of the same scene, "
            "options, seed and samples)");
  EXPECT_EQ(mergeError({vis, bandPart("gauss.exr", "gaussian:900@20", std::nullopt, 0, 2)}),
            "cannot stitch bands of different kinds (boxes, Gaussians and measured responses): "
            "render them with one kind of sensor");
}

ImagePart aovPart(const std::string& name, std::optional<PixelRect> crop, int first, int count) {
  RenderOptions o;
  o.whiteReference = true;
  o.components = o.lightGroups = true;
  return renderedPart(name, o, crop, first, count, /*geometryAovs=*/true);
}

// The AOVs merge with the rest: crops bit for bit, sample ranges averaged (white reference,
// component layers and their variances) or taken as they are (ids and depth, the same in every
// range).
TEST(Farm, AovsMergeLikeTheBands) {
  const SpectralImage full = aovPart("full", std::nullopt, 0, 4).image;
  ASSERT_FALSE(full.white.empty());
  const SpectralImage crops = mergeParts(
      {aovPart("a", PixelRect{0, 0, 40, 13}, 0, 4), aovPart("b", PixelRect{0, 13, 40, 30}, 0, 4)});
  EXPECT_EQ(crops.white, full.white);
  EXPECT_EQ(crops.objectId, full.objectId);
  EXPECT_EQ(crops.materialId, full.materialId);
  EXPECT_EQ(crops.depth, full.depth);
  ASSERT_EQ(full.layers.size(), 5u); // 4 path classes and the group "default"
  ASSERT_EQ(crops.layers.size(), full.layers.size());
  for (size_t l = 0; l < full.layers.size(); ++l) {
    EXPECT_EQ(crops.layers[l].name, full.layers[l].name);
    EXPECT_EQ(crops.layers[l].values, full.layers[l].values) << full.layers[l].name;
    EXPECT_EQ(crops.layers[l].variances, full.layers[l].variances) << full.layers[l].name;
  }
  const SpectralImage ranges =
      mergeParts({aovPart("r1", std::nullopt, 0, 1), aovPart("r2", std::nullopt, 1, 3)});
  ASSERT_EQ(ranges.white.size(), full.white.size());
  for (size_t i = 0; i < full.white.size(); ++i)
    ASSERT_NEAR(ranges.white[i], full.white[i], 1e-5f * (1 + full.white[i])) << i;
  EXPECT_EQ(ranges.objectId, full.objectId);
  EXPECT_EQ(ranges.depth, full.depth);
  ASSERT_EQ(ranges.layers.size(), full.layers.size());
  for (size_t l = 0; l < full.layers.size(); ++l)
    for (size_t i = 0; i < full.layers[l].values.size(); ++i)
      ASSERT_NEAR(ranges.layers[l].values[i], full.layers[l].values[i],
                  1e-5f * (1 + full.layers[l].values[i]))
          << full.layers[l].name << " " << i;
  // Parts with other layers do not merge.
  ImagePart plain = part("plain", std::nullopt, 1, 3);
  EXPECT_EQ(test::errorMessage([&] {
              mergeParts({aovPart("r1", std::nullopt, 0, 1), plain});
            }),
            "plain: does not belong with r1: its component layers are '', not "
            "'reflected,fluoresced,direct,indirect,light.default'");
}

// A render stopped part-way holds whole tiles with their true sample counts; resuming it
// ends with the uninterrupted image (up to float rounding of the stored means).
TEST(Farm, StopAndResumeEqualsUninterrupted) {
  RenderOptions o;
  o.samples = 12;
  o.passSamples = 4;
  const RenderOutput whole = render(scene(), o);

  std::atomic<bool> stop{false};
  o.stop = &stop;
  o.progress = [&](int64_t done, int64_t) {
    if (done == 9) stop = true; // part-way through the second pass
  };
  const RenderOutput partial = render(scene(), o);
  EXPECT_TRUE(partial.stats.stopped);
  uint64_t taken = 0;
  bool someBehind = false;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      // A stop takes effect before the next sample, so a pixel holds the first pass (4) and
      // any part of the second (up to 8).
      const uint32_t n = partial.film.samples(x, y);
      EXPECT_TRUE(n >= 4 && n <= 8) << n;
      someBehind = someBehind || n < 8;
      taken += n;
    }
  EXPECT_TRUE(someBehind);
  EXPECT_EQ(taken, partial.stats.samples);

  const Film stored = filmFromImage(toSpectralImage(partial.film), 0, 12);
  RenderOptions r;
  r.samples = 12;
  r.passSamples = 4;
  r.resumeFrom = &stored;
  const RenderOutput resumed = render(scene(), r);
  EXPECT_EQ(resumed.stats.samples + taken, 40u * 30u * 12u);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      EXPECT_EQ(resumed.film.samples(x, y), 12u);
      for (int b = 0; b < resumed.film.bands().count(); ++b)
        EXPECT_NEAR(resumed.film.bandMean(x, y, b), whole.film.bandMean(x, y, b),
                    2e-7 * std::max(1.0, std::abs(whole.film.bandMean(x, y, b))));
    }
}

// Crops rendered with different sample ranges have equal counts but not the same samples:
// merged, the image would record a range no pixel has. Refused, naming both.
TEST(Farm, CropsOfDifferentSampleRangesAreRefused) {
  const std::string message = test::errorMessage([] {
    mergeParts({part("top", PixelRect{0, 0, 40, 15}, 0, 4),
                part("bottom", PixelRect{0, 15, 40, 30}, 4, 4)});
  });
  EXPECT_EQ(message, "parts cover different sample ranges in different pixels: pixel 0,15 holds "
                     "samples 4:8, pixel 0,0 holds samples 0:4 (merge crops of the same range, "
                     "and ranges of the same pixels)");
}

// A partial with NaN pixels or impossible counts is refused, naming the pixel, rather than
// copied into the resumed output.
TEST(Farm, ResumeRefusesNonFiniteValuesAndImpossibleCounts) {
  RenderOptions o;
  o.samples = 4;
  const SpectralImage good = toSpectralImage(render(scene(), o).film);
  EXPECT_NO_THROW(filmFromImage(good, 0, 8));
  SpectralImage nan = good;
  nan.radiance[5 * static_cast<size_t>(good.bands.count()) + 1] = NAN;
  EXPECT_EQ(test::errorMessage([&] { filmFromImage(nan, 0, 8); }),
            "pixel 5,0: expected finite values >= 0 in the spectral channels to continue from, "
            "found nan");
  SpectralImage counts = good;
  counts.sampleCount[40 + 2] = 9; // pixel 2,1 of a 40-pixel-wide image
  EXPECT_EQ(test::errorMessage([&] { filmFromImage(counts, 0, 8); }),
            "pixel 2,1: expected at most the 8 samples of the render's range, found 9");
  SpectralImage variance = good;
  variance.yVariance[3] = -1;
  EXPECT_EQ(test::errorMessage([&] { filmFromImage(variance, 0, 8); }),
            "pixel 3,0: expected finite values >= 0 in Variance.Y to continue from, found -1");
}

} // namespace
} // namespace nx
