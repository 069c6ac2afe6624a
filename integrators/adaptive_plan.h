#pragma once
// Adaptive sampling: how many samples each block of pixels should hold so that the image's
// estimated error reaches a target in the least total samples.

#include <cstdint>
#include <vector>

#include "integrators/error_measure.h"
#include "integrators/film.h"

namespace nx {

/// Side of the square pixel blocks that share a sample count, on the full image's grid
/// (block (x / 8, y / 8)), so a crop of the image plans the same blocks.
inline constexpr int kAdaptiveBlock = 8;

/// Samples each block of a region should hold: a pure function of a film, so the same film
/// gives the same plan on any machine and thread count.
struct AdaptivePlan {
  PixelRect region;              ///< the pixels planned (a film's rectangle)
  int bx0 = 0, by0 = 0;          ///< the first block's grid position
  int blocksX = 0, blocksY = 0;  ///< blocks across and down
  std::vector<uint32_t> samples; ///< [block] samples its pixels should hold
  bool reachesTarget = false;    ///< false: even maxSamples everywhere misses the target
  /// Samples pixel (x, y) of the region should hold.
  uint32_t samplesAt(int x, int y) const {
    return samples[static_cast<size_t>(y / kAdaptiveBlock - by0) * blocksX +
                   static_cast<size_t>(x / kAdaptiveBlock - bx0)];
  }
  /// True when some pixel of `film` and of the region holds fewer samples than planned.
  bool addsSamplesTo(const Film& film) const;
};

/// Plans the samples of every block of the film's rectangle so that the estimated relative
/// RMS error of `measure` reaches `target` (aiming 10% below it). Each pixel's per-sample
/// variance is its estimated variance of the mean (two replicates) times its count,
/// normalised by the image's mean (luminance) or, for bands, the largest over the bands of
/// the band's value normalised by that band's mean; a block's is the mean over its pixels,
/// raised to half the mean of its 3x3 neighbourhood where that is larger (so that a block
/// whose pilot missed a rare path its neighbours found is not starved; half: the full mean
/// spent 15% more samples on the lab-bench scene for the same error). Samples then go to the
/// blocks in proportion to their per-sample standard deviation (the allocation that
/// minimises the image's summed variance for a given number of samples), never fewer than a
/// block's pixels hold, never more than maxSamples nor twice what the block holds (a round at
/// most doubles; the next round plans from better estimates), rounded up to even numbers
/// (both replicates alike). Every pixel needs two samples (one of each replicate) first.
AdaptivePlan planAdaptiveSamples(const Film& film, const ErrorMeasure& measure, double target,
                                 uint32_t maxSamples);

} // namespace nx
