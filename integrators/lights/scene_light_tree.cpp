// The scene's light tree: built top-down by the surface area orientation heuristic (Conty
// Estevez & Kulla 2018, section 4.4) over buckets of the lights' centroids.

#include "integrators/lights/scene_light_tree.h"

#include "integrators/lights/light_tree_split.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace nx {
namespace {

Vec3 centroidOf(const LightBounds& b) {
  return b.center();
}

// The heuristic's cost of a side: power M_A M_Omega (0 for an empty side).
double costOf(const LightBounds& b) {
  if (!(b.power > 0)) return 0;
  return static_cast<double>(b.power) * boxMeasure(b) *
         orientationMeasure(b.normals.cosSpread, b.cosEmission);
}

} // namespace

SceneLightTree::SceneLightTree(const std::vector<Item>& all, size_t lightCount, int bucketSize)
    : bucketSize_(std::clamp(bucketSize, 1, kMaxLightBucket)) {
  std::vector<Item> items;
  for (const Item& i : all)
    if (i.light >= 0 && static_cast<size_t>(i.light) < lightCount && i.bounds.power > 0 &&
        std::isfinite(i.bounds.power) && i.bounds.lo.x <= i.bounds.hi.x)
      items.push_back(i);
  bucketOf_.assign(lightCount, -1);
  slotOf_.assign(lightCount, 0);
  if (items.empty()) return;
  root_ = build(items, 0, items.size(), 0);
  if (root_ < 0) buckets_[static_cast<size_t>(-(root_ + 1))].parent = -1;
  // Parents of nodes and buckets, and the depth.
  parent_.assign(nodes_.size(), -1);
  side_.assign(nodes_.size(), 0);
  std::vector<int> level(nodes_.size(), 1);
  for (size_t i = 0; i < nodes_.size(); ++i)
    for (uint8_t s = 0; s < 2; ++s) {
      const Entry c = nodes_[i].child[s];
      if (c >= 0) {
        parent_[static_cast<size_t>(c)] = static_cast<int32_t>(i);
        side_[static_cast<size_t>(c)] = s;
        level[static_cast<size_t>(c)] = level[i] + 1; // children come after their parent
      } else {
        Bucket& b = buckets_[static_cast<size_t>(-(c + 1))];
        b.parent = static_cast<int32_t>(i);
        b.side = s;
        depth_ = std::max(depth_, level[i]);
      }
    }
}

SceneLightTree::Entry SceneLightTree::build(std::vector<Item>& items, size_t begin, size_t end,
                                            int depth) {
  if (end - begin <= static_cast<size_t>(bucketSize_)) {
    const int32_t b = static_cast<int32_t>(buckets_.size());
    buckets_.push_back(
        {static_cast<uint32_t>(lights_.size()), static_cast<uint32_t>(end - begin), -1, 0});
    for (size_t i = begin; i < end; ++i) {
      bucketOf_[static_cast<size_t>(items[i].light)] = b;
      slotOf_[static_cast<size_t>(items[i].light)] = static_cast<uint8_t>(i - begin);
      lights_.push_back(items[i].light);
    }
    return -(b + 1);
  }
  LightBounds all, centroids;
  for (size_t i = begin; i < end; ++i) {
    all = unionOf(all, items[i].bounds);
    centroids.add(centroidOf(items[i].bounds));
  }
  const Entry index = static_cast<Entry>(nodes_.size());
  nodes_.push_back({LightCluster(all), {kNone, kNone}});
  // The split of least cost summed over both sides, times the box's longest extent over its
  // extent along the axis (Conty Estevez & Kulla's regularisation against thin slabs).
  size_t mid = begin;
  if (depth < kLightTreeHeuristicDepth) {
    const Vec3 extent = all.hi - all.lo;
    const float longest = std::max({extent.x, extent.y, extent.z});
    double bestCost = INFINITY;
    int bestAxis = -1, bestSplit = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const float lo = centroids.lo[axis], hi = centroids.hi[axis];
      if (!(hi > lo)) continue;
      std::array<LightBounds, kLightTreeBuckets> buckets;
      for (size_t i = begin; i < end; ++i) {
        LightBounds& b = buckets[static_cast<size_t>(
            lightTreeBucket(centroidOf(items[i].bounds)[axis], lo, hi))];
        b = unionOf(b, items[i].bounds);
      }
      // Bounds of buckets [split, kLightTreeBuckets), swept from the top; [0, split) from the
      // bottom.
      std::array<LightBounds, kLightTreeBuckets> above;
      above[kLightTreeBuckets - 1] = buckets[kLightTreeBuckets - 1];
      for (int k = kLightTreeBuckets - 2; k >= 0; --k)
        above[static_cast<size_t>(k)] =
            unionOf(buckets[static_cast<size_t>(k)], above[static_cast<size_t>(k) + 1]);
      const double regular = extent[axis] > 0 ? longest / extent[axis] : 1.0;
      LightBounds below;
      for (int split = 1; split < kLightTreeBuckets; ++split) {
        below = unionOf(below, buckets[static_cast<size_t>(split) - 1]);
        const LightBounds& rest = above[static_cast<size_t>(split)];
        if (!(below.power > 0) || !(rest.power > 0)) continue;
        const double cost = regular * (costOf(below) + costOf(rest));
        if (cost < bestCost) bestCost = cost, bestAxis = axis, bestSplit = split;
      }
    }
    if (bestAxis >= 0) {
      const float lo = centroids.lo[bestAxis], hi = centroids.hi[bestAxis];
      const auto split = std::partition(
          items.begin() + static_cast<std::ptrdiff_t>(begin),
          items.begin() + static_cast<std::ptrdiff_t>(end), [&](const Item& i) {
            return lightTreeBucket(centroidOf(i.bounds)[bestAxis], lo, hi) < bestSplit;
          });
      mid = static_cast<size_t>(split - items.begin());
    }
  }
  if (mid <= begin || mid >= end) {
    // No useful split (coincident lights, or deep): halves along the longest axis.
    mid = splitAtMedian(items, begin, end, centroids,
                        [](const Item& i) { return centroidOf(i.bounds); });
  }
  const Entry first = build(items, begin, mid, depth + 1);
  const Entry second = build(items, mid, end, depth + 1);
  nodes_[static_cast<size_t>(index)].child[0] = first;
  nodes_[static_cast<size_t>(index)].child[1] = second;
  return index;
}

} // namespace nx
