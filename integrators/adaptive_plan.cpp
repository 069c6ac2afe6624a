#include "integrators/adaptive_plan.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace nx {

bool AdaptivePlan::addsSamplesTo(const Film& film) const {
  const PixelRect& f = film.rect();
  for (int y = std::max(region.y0, f.y0); y < std::min(region.y1, f.y1); ++y)
    for (int x = std::max(region.x0, f.x0); x < std::min(region.x1, f.x1); ++x)
      if (film.samples(x, y) < samplesAt(x, y)) return true;
  return false;
}

namespace {

// Each pixel's per-sample variance, normalised so that the target is a mean of target^2.
// True when the measured quantity (luminance, or a band the measure names) is above 0 somewhere.
bool measuredSignal(const Film& film, const ErrorMeasure& measure) {
  const PixelRect& r = film.rect();
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      if (!measure.bands) {
        if (film.xyzMean(x, y).y > 0) return true;
        continue;
      }
      for (int b = 0; b < film.bands().count(); ++b) {
        const double c = film.bands().centroid(b);
        if (c >= measure.loNm && c <= measure.hiNm && film.bandMean(x, y, b) > 0) return true;
      }
    }
  return false;
}

std::vector<double> normalisedSampleVariances(const Film& film, const ErrorMeasure& measure) {
  const PixelRect& r = film.rect();
  const size_t pixels = static_cast<size_t>(r.width()) * r.height();
  std::vector<double> v(pixels, 0.0);
  auto at = [&](int x, int y) {
    return static_cast<size_t>(y - r.y0) * r.width() + static_cast<size_t>(x - r.x0);
  };
  if (!measure.bands) {
    double meanY = 0;
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) meanY += film.xyzMean(x, y).y;
    meanY /= static_cast<double>(pixels);
    if (!(meanY > 0)) return v; // a black image: nothing to gain from more samples
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x)
        v[at(x, y)] = film.yVariance(x, y) * film.samples(x, y) / (meanY * meanY);
    return v;
  }
  const int nb = film.bands().count();
  for (int b = 0; b < nb; ++b) {
    const double c = film.bands().centroid(b);
    if (c < measure.loNm || c > measure.hiNm) continue;
    double mean = 0;
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) mean += film.bandMean(x, y, b);
    mean /= static_cast<double>(pixels);
    if (!(mean > 0)) continue; // a black band has no relative error (skipped by the measure too)
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x)
        v[at(x, y)] =
            std::max(v[at(x, y)], film.bandVariance(x, y, b) * film.samples(x, y) / (mean * mean));
  }
  return v;
}

uint32_t roundUpEven(double n) {
  const double c = std::ceil(n);
  const auto k = static_cast<uint32_t>(std::min(c, 4.0e9));
  return k + (k & 1U);
}

} // namespace

AdaptivePlan planAdaptiveSamples(const Film& film, const ErrorMeasure& measure, double target,
                                 uint32_t maxSamples) {
  if (!(target > 0)) throw Error("adaptive sampling: expected a target error > 0");
  const PixelRect& r = film.rect();
  AdaptivePlan plan;
  plan.region = r;
  plan.bx0 = r.x0 / kAdaptiveBlock;
  plan.by0 = r.y0 / kAdaptiveBlock;
  plan.blocksX = (r.x1 - 1) / kAdaptiveBlock - plan.bx0 + 1;
  plan.blocksY = (r.y1 - 1) / kAdaptiveBlock - plan.by0 + 1;
  const size_t blocks = static_cast<size_t>(plan.blocksX) * plan.blocksY;

  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x)
      if (film.samples(x, y) < 2)
        throw Error("adaptive sampling: pixel " + std::to_string(x) + "," + std::to_string(y) +
                    " holds fewer than the two samples (one per replicate) a plan needs");

  measure.requireBandsIn(film.bands());
  // Per block: pixels, summed per-sample variance, the fewest samples a pixel holds.
  const std::vector<double> v = normalisedSampleVariances(film, measure);
  // A lit image whose every variance estimate is 0 has had its variances removed or zeroed
  // (no render of two replicates gives that): a plan from it would add no sample and call the
  // error 0.
  if (std::all_of(v.begin(), v.end(), [](double x) { return x == 0; }) &&
      measuredSignal(film, measure))
    throw Error("adaptive sampling: expected variance estimates to plan from, found 0 at every "
                "pixel of an image that is not black (variances removed, e.g. --no-variance, "
                "or zeroed)");
  std::vector<double> pixelsIn(blocks, 0.0), sum(blocks, 0.0);
  std::vector<uint32_t> held(blocks, maxSamples);
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const size_t b = static_cast<size_t>(y / kAdaptiveBlock - plan.by0) * plan.blocksX +
                       static_cast<size_t>(x / kAdaptiveBlock - plan.bx0);
      pixelsIn[b] += 1;
      sum[b] += v[static_cast<size_t>(y - r.y0) * r.width() + static_cast<size_t>(x - r.x0)];
      held[b] = std::min(held[b], film.samples(x, y));
    }
  std::vector<double> sigma(blocks), raised(blocks);
  for (size_t b = 0; b < blocks; ++b) sigma[b] = std::sqrt(sum[b] / pixelsIn[b]);
  for (int j = 0; j < plan.blocksY; ++j)
    for (int i = 0; i < plan.blocksX; ++i) {
      double s = 0, n = 0;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int a = i + di, c = j + dj;
          if (a < 0 || c < 0 || a >= plan.blocksX || c >= plan.blocksY) continue;
          s += sigma[static_cast<size_t>(c) * plan.blocksX + a];
          n += 1;
        }
      const size_t b = static_cast<size_t>(j) * plan.blocksX + i;
      raised[b] = std::max(sigma[b], 0.5 * s / n);
    }

  // Samples n_b = clamp(sigma_b / lambda, held_b, max): the summed variance
  // sum_b pixels_b sigma_b^2 / n_b grows with lambda; find the lambda that meets the target
  // (bisection in log lambda), aiming 10% below the target so one round usually suffices.
  const double total = static_cast<double>(r.width()) * r.height();
  const double allowed = (0.9 * target) * (0.9 * target) * total;
  auto countFor = [&](size_t b, double lambda) {
    return std::clamp(raised[b] / lambda, static_cast<double>(held[b]),
                      static_cast<double>(maxSamples));
  };
  auto varianceFor = [&](double lambda) {
    double s = 0;
    for (size_t b = 0; b < blocks; ++b)
      s += pixelsIn[b] * raised[b] * raised[b] / countFor(b, lambda);
    return s;
  };
  double lo = -80, hi = 80; // log lambda
  plan.reachesTarget = varianceFor(std::exp(lo)) <= allowed;
  if (!plan.reachesTarget) lo = hi = -80; // every block to the most it may take (below)
  for (int it = 0; it < 200 && hi - lo > 1e-9 && plan.reachesTarget; ++it) {
    const double mid = 0.5 * (lo + hi);
    (varianceFor(std::exp(mid)) <= allowed ? lo : hi) = mid;
  }
  plan.samples.resize(blocks);
  for (size_t b = 0; b < blocks; ++b) {
    // A round at most doubles a block's samples: the next round plans from better estimates,
    // and the round that meets the target overshoots it by at most a factor 2 in samples.
    const double grown = std::min(countFor(b, std::exp(lo)), 2.0 * held[b]);
    plan.samples[b] = std::min(maxSamples, roundUpEven(grown));
  }
  return plan;
}

} // namespace nx
