#pragma once
// What the two light-tree builders (MeshLightTree, SceneLightTree) share: the buckets of
// centroids the split heuristic sweeps, the depth beyond which they split at the median, and
// that median split.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "integrators/lights/light_bounds.h"

namespace nx {

/// Splits deeper than this are made at the median (a balanced tree below, whatever the
/// heuristic would do with degenerate inputs).
inline constexpr int kLightTreeHeuristicDepth = 48;
/// Buckets of centroids along each axis the split heuristic tries.
inline constexpr int kLightTreeBuckets = 12;

/// The bucket of a centroid coordinate x in [lo, hi] (hi > lo).
inline int lightTreeBucket(float x, float lo, float hi) {
  return std::min(kLightTreeBuckets - 1,
                  static_cast<int>(kLightTreeBuckets * ((x - lo) / (hi - lo))));
}

/// Halves items[begin, end) along the longest axis of their centroids' box (`centroids`,
/// centroidOf(item) giving each): the fallback where no heuristic split separates them.
/// Returns the middle.
template <class Item, class CentroidOf>
size_t splitAtMedian(std::vector<Item>& items, size_t begin, size_t end,
                     const LightBounds& centroids, CentroidOf centroidOf) {
  const Vec3 e = centroids.hi - centroids.lo;
  const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
  const size_t mid = begin + (end - begin) / 2;
  std::nth_element(
      items.begin() + static_cast<std::ptrdiff_t>(begin),
      items.begin() + static_cast<std::ptrdiff_t>(mid),
      items.begin() + static_cast<std::ptrdiff_t>(end),
      [&](const Item& a, const Item& b) { return centroidOf(a)[axis] < centroidOf(b)[axis]; });
  return mid;
}

} // namespace nx
