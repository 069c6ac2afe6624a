#pragma once
// Noise of a render measured the direct way: the same scene rendered with several seeds, per
// pixel and band (and per pixel in luminance) the spread of one render's value about the mean.

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "apps/bench_util.h"
#include "integrators/renderer.h"

namespace nx::bench {

/// Per-pixel, per-band (and per-pixel luminance) sums over renders with different seeds.
struct SeedStatistics {
  int width = 0, height = 0, bands = 0, renders = 0, samples = 0;
  std::vector<double> sum, sumSquares;   ///< per (pixel, band)
  std::vector<double> sumY, sumSquaresY; ///< per pixel, luminance Y
  std::vector<double> centroids;         ///< per band (nm)
  double nsPerSample = 0;                ///< the fastest render's time per pixel sample
  /// Mean of (x, y, band b).
  double mean(int x, int y, int b) const { return sum[index(x, y, b)] / renders; }
  /// Relative standard deviation of one render's value at (x, y, b); 0 where the mean is 0.
  double relativeNoise(int x, int y, int b) const {
    return relative(sum[index(x, y, b)], sumSquares[index(x, y, b)]);
  }
  /// Mean luminance of pixel (x, y).
  double meanY(int x, int y) const { return sumY[pixel(x, y)] / renders; }
  /// Relative standard deviation of one render's luminance at (x, y).
  double relativeNoiseY(int x, int y) const {
    return relative(sumY[pixel(x, y)], sumSquaresY[pixel(x, y)]);
  }
  /// Index of pixel (x, y).
  size_t pixel(int x, int y) const { return static_cast<size_t>(y) * width + x; }
  /// Index of (x, y, band b).
  size_t index(int x, int y, int b) const { return pixel(x, y) * bands + b; }

private:
  double relative(double s, double s2) const {
    const double m = s / renders;
    const double v = (s2 - renders * m * m) / (renders - 1);
    return m > 0 ? std::sqrt(std::max(v, 0.0)) / m : 0;
  }
};

/// `renders` renders of scene with options o at seeds 1000, 1001, ...
inline SeedStatistics seedStatistics(const RenderScene& scene, RenderOptions o, int renders) {
  SeedStatistics s;
  s.renders = renders;
  s.samples = o.samples > 0 ? o.samples : scene.settings.samples;
  double fastest = 1e300;
  for (int r = 0; r < renders; ++r) {
    o.seed = 1000u + static_cast<uint32_t>(r);
    std::optional<RenderOutput> out;
    fastest = std::min(fastest, fastestSeconds(1, [&] { out = render(scene, o); }));
    const Film& f = out->film;
    if (r == 0) {
      s.width = f.width();
      s.height = f.height();
      s.bands = f.bands().count();
      s.sum.assign(static_cast<size_t>(s.width) * s.height * s.bands, 0);
      s.sumSquares = s.sum;
      s.sumY.assign(static_cast<size_t>(s.width) * s.height, 0);
      s.sumSquaresY = s.sumY;
      for (int b = 0; b < s.bands; ++b) s.centroids.push_back(f.bands().centroid(b));
    }
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        for (int b = 0; b < s.bands; ++b) {
          const double v = f.bandMean(x, y, b);
          s.sum[s.index(x, y, b)] += v;
          s.sumSquares[s.index(x, y, b)] += v * v;
        }
        const double luminance = f.xyzMean(x, y).y;
        s.sumY[s.pixel(x, y)] += luminance;
        s.sumSquaresY[s.pixel(x, y)] += luminance * luminance;
      }
  }
  s.nsPerSample = fastest * 1e9 / (static_cast<double>(s.width) * s.height * s.samples);
  return s;
}

/// Mean relative noise over the (pixel, band) pairs `take` selects.
inline double meanRelativeNoise(const SeedStatistics& s,
                                const std::function<bool(int x, int y, int b)>& take) {
  double total = 0;
  long n = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      for (int b = 0; b < s.bands; ++b)
        if (take(x, y, b)) {
          total += s.relativeNoise(x, y, b);
          ++n;
        }
  return n ? total / static_cast<double>(n) : 0;
}

/// Mean relative noise over every pixel and band whose mean is above 1% of the image's
/// brightest value.
inline double litNoise(const SeedStatistics& s) {
  double brightest = 0;
  for (double v : s.sum) brightest = std::max(brightest, v / s.renders);
  return meanRelativeNoise(s,
                           [&](int x, int y, int b) { return s.mean(x, y, b) > 0.01 * brightest; });
}

/// Mean relative luminance noise over pixels whose luminance is above 1% of the brightest.
inline double litNoiseY(const SeedStatistics& s) {
  double brightest = 0;
  for (double v : s.sumY) brightest = std::max(brightest, v / s.renders);
  double total = 0;
  long n = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      if (s.meanY(x, y) > 0.01 * brightest) {
        total += s.relativeNoiseY(x, y);
        ++n;
      }
  return n ? total / static_cast<double>(n) : 0;
}

} // namespace nx::bench
