#include <gtest/gtest.h>

#include <cmath>

#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "support/render_checks.h"

namespace nx {
namespace {

const char* kScene =
    "<scene><settings><xres>64</xres><yres>48</yres><mode>spectral_mcpt</mode><depth>3</"
    "depth><sampl>4096</sampl>"
    "<background>0.2</background>"
    "</settings><camera><position>0,2,-5</position><look_at>0,0.7,0</look_at></camera>"
    "<plane><normal>0,1,0</normal><distance>0</distance><material>matte</"
    "material><reflectance>0.6</reflectance></plane>"
    "<sphere><center>0,0.7,0</center><radius>0.7</radius><material>matte</"
    "material><reflectance>blue</reflectance></sphere>"
    "<sphere><center>2,4,-2</center><radius>1.5</radius><material>matte</material><emission>1</"
    "emission></sphere>"
    "</scene>";

const RenderScene& scene() {
  static const RenderScene s = buildRenderScene(parseScene(kScene, "convergence.scn"));
  return s;
}

// The per-pixel variance estimate predicts the actual error: --target-error stops at a sample
// count whose error against an independent reference is within a factor 1.5 of the target.
TEST(Convergence, TargetErrorStopsNearTheTarget) {
  RenderOptions refOptions;
  refOptions.samples = 4096;
  refOptions.seed = 99; // independent of the renders below
  const RenderOutput ref = render(scene(), refOptions);
  for (double target : {0.03, 0.015, 0.008}) {
    RenderOptions o;
    o.samples = 4096;
    o.targetRelativeError = target;
    const RenderOutput out = render(scene(), o);
    ASSERT_TRUE(out.stats.reachedTarget) << target;
    EXPECT_LE(out.stats.relativeError, target);
    const double measured = relativeLuminanceError(out.film, ref.film);
    EXPECT_GT(measured, target / 1.5)
        << "target " << target << " at " << out.stats.samplesReached << " spp";
    EXPECT_LT(measured, target * 1.5)
        << "target " << target << " at " << out.stats.samplesReached << " spp";
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x)
        ASSERT_EQ(out.film.samples(x, y), static_cast<uint32_t>(out.stats.samplesReached));
    // Deterministic for the sample count reached: the same as asking for that count.
    RenderOptions fixed;
    fixed.samples = out.stats.samplesReached;
    const RenderOutput same = render(scene(), fixed);
    EXPECT_EQ(same.film.bandMean(10, 10, 5), out.film.bandMean(10, 10, 5));
  }
}

// --time-limit: no pass starts that would end past the limit (judged by the previous pass),
// so the render ends within one pass of the limit. A simulated clock (0.01 s per finished
// tile) makes this independent of the machine's speed.
TEST(Convergence, TimeLimitEndsWithinOnePass) {
  for (double limit : {0.05, 0.5, 2.0}) {
    std::atomic<int64_t> tiles{0};
    RenderOptions o;
    o.samples = 4096;
    o.timeLimitSeconds = limit;
    o.progress = [&](int64_t done, int64_t) { tiles = done; };
    o.clock = [&] { return 0.01 * static_cast<double>(tiles.load()); };
    const RenderOutput out = render(scene(), o);
    const double passSeconds = 0.01 * 12; // 64x48 pixels = 12 tiles of 16x16 per pass
    const double ended = 0.01 * static_cast<double>(tiles.load());
    EXPECT_TRUE(out.stats.reachedTimeLimit);
    EXPECT_LE(ended, std::max(limit, passSeconds) + 1e-9) << limit;
    EXPECT_GT(ended + passSeconds, limit - 1e-9) << limit; // and did not stop early
    EXPECT_EQ(out.stats.samplesReached, static_cast<int>(std::lround(ended / passSeconds)) * 8);
  }
}

} // namespace
} // namespace nx

namespace nx {
namespace {

// Measured relative RMS error of band b against a reference.
double measuredBandError(const Film& film, const Film& ref, int b) {
  double se = 0, mean = 0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      const double d = film.bandMean(x, y, b) - ref.bandMean(x, y, b);
      se += d * d;
      mean += ref.bandMean(x, y, b);
    }
  const double n = film.width() * film.height();
  return std::sqrt(se / n) / (mean / n);
}

// --error-of bands: the render stops when its worst band (among those asked for) reaches the
// target, and that band's error against an independent reference is near the target; the
// bands outside the range asked for are not what stopped it.
TEST(Convergence, TargetErrorOnTheBands) {
  const Sensor bands(SpectralBands::parse("420:980:80"));
  RenderOptions refOptions;
  refOptions.samples = 2048;
  refOptions.seed = 99;
  refOptions.bands = bands;
  const RenderOutput ref = render(scene(), refOptions);
  for (auto [lo, hi] : {std::pair{0.0, 1e9}, std::pair{850.0, 1000.0}}) {
    RenderOptions o;
    o.samples = 2048;
    o.bands = bands;
    o.targetRelativeError = 0.06;
    o.errorMeasure = {true, lo, hi};
    const RenderOutput out = render(scene(), o);
    ASSERT_TRUE(out.stats.reachedTarget);
    EXPECT_LE(out.stats.relativeError, 0.06);
    EXPECT_LT(out.stats.samplesReached, 2048);
    double worst = 0, estimatedWorst = 0;
    for (int b = 0; b < bands.count(); ++b) {
      if (bands.centroid(b) < lo || bands.centroid(b) > hi) continue;
      worst = std::max(worst, measuredBandError(out.film, ref.film, b));
      estimatedWorst = std::max(estimatedWorst, out.film.bandRelativeRmsError(b));
    }
    EXPECT_EQ(estimatedWorst, out.stats.relativeError);
    EXPECT_GT(worst, 0.06 / 1.5) << lo << "-" << hi << " at " << out.stats.samplesReached;
    EXPECT_LT(worst, 0.06 * 1.5) << lo << "-" << hi << " at " << out.stats.samplesReached;
  }
}

} // namespace
} // namespace nx
