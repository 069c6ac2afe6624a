// Adaptive sampling: the plan's allocation, determinism across thread counts and farm
// crops, and the error target met against an independent reference.

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "integrators/adaptive_plan.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "support/errors.h"
#include "support/render_checks.h"

namespace nx {
namespace {

// Uneven noise: a glass sphere focusing a small light onto a matte floor (a caustic, found
// by BSDF sampling only), a matte sphere beside it, and a uniform sky that has no noise.
const char* kScene =
    "<scene><settings><xres>48</xres><yres>32</yres><mode>spectral_mcpt</mode><depth>5</"
    "depth><sampl>4096</sampl><background>0.05</background></settings>"
    "<camera><position>0,2.2,-5</position><look_at>0,0.3,0</look_at></camera>"
    "<plane><normal>0,1,0</normal><distance>0</distance><material>matte</material>"
    "<reflectance>0.7</reflectance></plane>"
    "<sphere><center>-0.3,0.7,0</center><radius>0.7</radius><material>glass</material></sphere>"
    "<sphere><center>1.4,0.5,0.5</center><radius>0.5</radius><material>matte</material>"
    "<reflectance>0.5</reflectance></sphere>"
    "<sphere><center>-0.6,3,0.6</center><radius>0.15</radius><material>matte</material>"
    "<emission>60</emission></sphere>"
    "</scene>";

const RenderScene& scene() {
  static const RenderScene s = buildRenderScene(parseScene(kScene, "adaptive.scn"));
  return s;
}

// Every pixel's count and every band mean equal, bit for bit, over a rectangle.
void expectSameFilm(const Film& a, const Film& b, const PixelRect& r) {
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      ASSERT_EQ(a.samples(x, y), b.samples(x, y)) << x << "," << y;
      for (int k = 0; k < a.bands().count(); ++k)
        ASSERT_EQ(a.bandMean(x, y, k), b.bandMean(x, y, k)) << x << "," << y << " band " << k;
      ASSERT_EQ(a.yVariance(x, y), b.yVariance(x, y)) << x << "," << y;
    }
}

RenderOptions adaptiveOptions(double target) {
  RenderOptions o;
  o.samples = 4096;
  o.adaptive = true;
  o.targetRelativeError = target;
  return o;
}

// The error target is met (estimated) and the error against an independent reference lies
// within a factor 1.5 of it; the samples went where the noise is (the caustic's blocks hold
// many times the sky's), and fewer in total than a uniform render needs for that error.
TEST(Adaptive, MeetsTheTargetAgainstAnIndependentReference) {
  RenderOptions refOptions;
  refOptions.samples = 8192;
  refOptions.seed = 99;
  const RenderOutput ref = render(scene(), refOptions);
  for (double target : {0.12, 0.07}) {
    const RenderOutput out = render(scene(), adaptiveOptions(target));
    ASSERT_TRUE(out.stats.reachedTarget) << target;
    EXPECT_LE(out.stats.relativeError, target);
    const double measured = relativeLuminanceError(out.film, ref.film);
    const double meanSpp = static_cast<double>(out.stats.samples) / (48.0 * 32.0);
    EXPECT_GT(measured, target / 1.5) << "target " << target << ", " << meanSpp << " spp";
    EXPECT_LT(measured, target * 1.5) << "target " << target << ", " << meanSpp << " spp";
    uint32_t fewest = 1u << 30, most = 0;
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 48; ++x)
        fewest = std::min(fewest, out.film.samples(x, y)),
        most = std::max(most, out.film.samples(x, y));
    EXPECT_GE(most, 4 * fewest) << "the caustic's blocks against the quietest";
    std::printf("target %g: error %.4f against the reference, %.1f spp on average, %u to %u\n",
                target, measured, meanSpp, fewest, most);
    // Uniform sampling at the same total samples has a larger error.
    RenderOptions uniform;
    uniform.samples = static_cast<int>(std::ceil(meanSpp));
    EXPECT_GT(relativeLuminanceError(render(scene(), uniform).film, ref.film), 1.2 * measured)
        << target;
  }
}

// The same adaptive render on one thread and on two, and with other tile sizes: the same
// counts and values bit for bit (every decision is made between passes from the film).
TEST(Adaptive, DeterministicAcrossThreadCounts) {
  RenderOptions o = adaptiveOptions(0.1);
  const RenderOutput two = render(scene(), o);
  tbb::task_arena one(1);
  o.tileSize = 5;
  const RenderOutput single = one.execute([&] { return render(scene(), o); });
  EXPECT_EQ(single.stats.adaptiveRounds, two.stats.adaptiveRounds);
  expectSameFilm(single.film, two.film, {0, 0, 48, 32});
}

// A farm round: every crop part plans from the whole pilot image and continues its crop;
// the crops (cut across plan blocks) hold exactly what the unsplit round holds.
TEST(Adaptive, FarmCropsOfARoundEqualTheWholeRound) {
  RenderOptions pilotOptions;
  pilotOptions.samples = 16;
  const RenderOutput pilot = render(scene(), pilotOptions);
  const AdaptivePlan plan = planAdaptiveSamples(pilot.film, ErrorMeasure{}, 0.05, 4096);
  ASSERT_TRUE(plan.addsSamplesTo(pilot.film));
  RenderOptions round = adaptiveOptions(0.05);
  round.adaptivePlan = &plan;
  round.resumeFrom = &pilot.film;
  const RenderOutput whole = render(scene(), round);
  EXPECT_EQ(whole.stats.adaptiveRounds, 1);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 48; ++x) ASSERT_EQ(whole.film.samples(x, y), plan.samplesAt(x, y));
  for (const PixelRect crop :
       {PixelRect{0, 0, 19, 32}, PixelRect{19, 0, 48, 13}, PixelRect{19, 13, 48, 32}}) {
    const Film start = pilot.film.cropped(crop);
    RenderOptions part = round;
    part.crop = crop;
    part.resumeFrom = &start;
    expectSameFilm(render(scene(), part).film, whole.film, crop);
  }
}

// The plan: samples in proportion to each block's per-sample standard deviation, the
// model's summed variance at the target, nothing for black images, at most a doubling per
// round, never more than the most allowed.
TEST(Adaptive, PlanAllocatesByStandardDeviation) {
  const Sensor bands(SpectralBands::parse("500:600:50"));
  const size_t nb = static_cast<size_t>(bands.count());
  // 32x8 pixels: four blocks; per-sample standard deviations 1, 1.3, 1.6, 0 (no noise).
  auto filmWith = [&](uint32_t n) {
    Film f(32, 8, bands);
    const std::vector<float> means(nb, 1.0f);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 32; ++x) {
        const double sigma = x < 8 ? 1 : x < 16 ? 1.3 : x < 24 ? 1.6 : 0;
        const std::vector<float> vars(nb, static_cast<float>(sigma * sigma / n));
        const double xyz[3] = {1, 1, 1};
        f.setFromMeans(x, y, means.data(), vars.data(), xyz, sigma * sigma / n, n, n / 2);
      }
    return f;
  };
  // Raised by the neighbourhood to max(own, half the mean of the 3x3 blocks around it).
  const double raised[4] = {1.0, 1.3, 1.6, 0.4};
  const Film g = filmWith(16);
  const AdaptivePlan plan = planAdaptiveSamples(g, ErrorMeasure{}, 0.3, 1u << 20);
  ASSERT_EQ(plan.blocksX, 4);
  ASSERT_EQ(plan.blocksY, 1);
  ASSERT_TRUE(plan.reachesTarget);
  // Block 1 is inside its bounds (16 held, at most 32 this round): its count gives the scale.
  ASSERT_GT(plan.samples[1], 16u);
  ASSERT_LT(plan.samples[1], 32u);
  const double scale = plan.samples[1] / raised[1];
  double modelVariance = 0;
  for (int b = 0; b < 4; ++b) {
    EXPECT_NEAR(plan.samples[b], std::clamp(raised[b] * scale, 16.0, 32.0), 2.0) << b;
    modelVariance += 64.0 * raised[b] * raised[b] / plan.samples[b];
  }
  // The model's variance per pixel at the plan: (0.9 target)^2, a little below from rounding.
  EXPECT_LE(modelVariance / 256.0, 0.27 * 0.27 * 1.0001);
  EXPECT_GT(modelVariance / 256.0, 0.27 * 0.27 * 0.85);
  // Far from the target a round doubles; maxSamples caps it.
  const AdaptivePlan doubling = planAdaptiveSamples(filmWith(64), ErrorMeasure{}, 0.01, 1000);
  for (int b = 0; b < 3; ++b) EXPECT_EQ(doubling.samples[b], 128u) << b;
  const AdaptivePlan capped = planAdaptiveSamples(filmWith(64), ErrorMeasure{}, 0.001, 100);
  EXPECT_FALSE(capped.reachesTarget);
  for (uint32_t s : capped.samples) EXPECT_EQ(s, 100u);
  // A black image plans nothing more.
  Film black(16, 8, bands);
  const std::vector<float> zero(nb, 0.0f);
  const double xyz0[3] = {0, 0, 0};
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) black.setFromMeans(x, y, zero.data(), zero.data(), xyz0, 0, 4, 2);
  EXPECT_FALSE(planAdaptiveSamples(black, ErrorMeasure{}, 0.1, 64).addsSamplesTo(black));
  // A pixel with fewer than two samples cannot be planned.
  Film thin(8, 8, bands);
  EXPECT_NE(test::errorMessage([&] {
              planAdaptiveSamples(thin, ErrorMeasure{}, 0.1, 64);
            }).find("fewer than the two samples"),
            std::string::npos);
}

// An adaptive render needs a target and two samples per pixel.
TEST(Adaptive, NeedsATargetAndTwoSamples) {
  RenderOptions o;
  o.samples = 16;
  o.adaptive = true;
  EXPECT_NE(test::errorMessage([&] { render(scene(), o); }).find("needs a target error"),
            std::string::npos);
  o.targetRelativeError = 0.1;
  o.samples = 1;
  EXPECT_NE(test::errorMessage([&] { render(scene(), o); }).find("at least 2 samples per pixel"),
            std::string::npos);
  // Two samples: the pilot is the whole render.
  o.samples = 2;
  const RenderOutput two = render(scene(), o);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 48; ++x) ASSERT_EQ(two.film.samples(x, y), 2u);
}

} // namespace
} // namespace nx
