#pragma once
// A light BVH over all of a scene's bounded lights (point and spot lights, emitting spheres,
// meshes and triangles): next-event estimation walks it from the root, choosing each child in
// proportion to the light its cluster can send to the shading point (LightCluster::importance,
// whose bounds carry each emitter's directional extent: a spot's cone, an area light's normals),
// and at the leaves the light's own weight (Conty Estevez & Kulla, "Importance Sampling of Many
// Lights with Adaptive Tree Splitting", HPG 2018). Cost per choice grows with the log of the
// number of lights instead of the number.

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "integrators/lights/light_bounds.h"

namespace nx {

/// Most lights in one bucket of a SceneLightTree.
inline constexpr int kMaxLightBucket = 64;

/// A binary light tree over lights numbered by the caller, whose leaves are buckets of up to
/// `bucketSize` lights. A bucket is weighed by the sum of its lights' exact weights (a function
/// the caller passes, positive wherever the light can shine) and chooses among them by those
/// weights; inner nodes are weighed by their clusters' importance. A tree of at most bucketSize
/// lights is thus the exact choice by weight, and the walks down (choose) and up (probability)
/// agree. Nothing is allocated after construction.
class SceneLightTree {
public:
  /// A light the tree is built over: its number and its bounds (power in the leaf weight's
  /// units: weight ~ power cos / d^2 far away).
  struct Item {
    int32_t light;
    LightBounds bounds;
  };

  SceneLightTree() = default;
  /// The tree over `items` (those of positive, finite power; numbers below `lightCount`),
  /// buckets of at most bucketSize (1 to kMaxLightBucket) lights.
  SceneLightTree(const std::vector<Item>& items, size_t lightCount, int bucketSize);

  /// True when it holds no light.
  bool empty() const { return root_ == kNone; }
  /// Whether light k is in the tree.
  bool holds(int k) const {
    return static_cast<size_t>(k) < bucketOf_.size() && bucketOf_[static_cast<size_t>(k)] >= 0;
  }
  /// Weight of the whole tree at (p, n): the root's importance, or its bucket's weight.
  template <class LeafWeight>
  float weight(const Vec3& p, const Vec3& n, const LeafWeight& leafWeight) const {
    return empty() ? 0.0f : weightOf(root_, p, n, leafWeight, nullptr);
  }
  /// A light chosen by walking down from the root with u in [0, 1) (rescaled into the chosen
  /// light's share, for its own choice of triangle), each child in proportion to its weight at
  /// (p, n) (n zero: no receiver), and the probability of that choice; -1 when nothing can
  /// light p.
  template <class LeafWeight>
  int choose(const Vec3& p, const Vec3& n, double& u, double& probability,
             const LeafWeight& leafWeight) const;
  /// The probability with which choose() returns light k at (p, n) (0 when it never does).
  template <class LeafWeight>
  double probability(int k, const Vec3& p, const Vec3& n, const LeafWeight& leafWeight) const;

  /// Number of inner nodes.
  size_t nodeCount() const { return nodes_.size(); }
  /// Number of buckets.
  size_t bucketCount() const { return buckets_.size(); }
  /// Levels of inner nodes above the deepest bucket (one bucket alone: 0).
  int depth() const { return depth_; }

private:
  /// An entry: an inner node (>= 0) or bucket b as -(b + 1).
  using Entry = int32_t;
  static constexpr Entry kNone = INT32_MIN;
  struct Node {
    LightCluster cluster;
    Entry child[2];
  };
  struct Bucket {
    uint32_t first, count; ///< its lights in lights_
    int32_t parent;        ///< its node, -1 for the root
    uint8_t side;          ///< which child of its node it is
  };
  using BucketWeights = std::array<float, kMaxLightBucket>;
  /// Weight of entry e at (p, n); a bucket's lights' weights are kept in `keep` (if not null).
  template <class LeafWeight>
  float weightOf(Entry e, const Vec3& p, const Vec3& n, const LeafWeight& leafWeight,
                 BucketWeights* keep) const {
    if (e < 0) {
      const Bucket& b = buckets_[static_cast<size_t>(-(e + 1))];
      float total = 0;
      for (uint32_t i = 0; i < b.count; ++i) {
        const float w = leafWeight(lights_[b.first + i]);
        if (keep) (*keep)[i] = w;
        total += w;
      }
      return total;
    }
    const LightCluster& c = nodes_[static_cast<size_t>(e)].cluster;
    return c.importance(p, n, c.twoSided);
  }
  /// Builds the entry over items[begin, end) at `depth`.
  Entry build(std::vector<Item>& items, size_t begin, size_t end, int depth);

  int bucketSize_ = 1;
  std::vector<Node> nodes_;
  std::vector<int32_t> parent_; ///< per node: its parent, -1 for the root
  std::vector<uint8_t> side_;   ///< per node: which child of its parent it is
  std::vector<Bucket> buckets_;
  std::vector<int32_t> lights_;   ///< the buckets' lights, bucket by bucket
  std::vector<int32_t> bucketOf_; ///< per light: its bucket, or -1 if absent
  std::vector<uint8_t> slotOf_;   ///< per light: its place in its bucket
  Entry root_ = kNone;
  int depth_ = 0;
};

template <class LeafWeight>
int SceneLightTree::choose(const Vec3& p, const Vec3& n, double& u, double& probability,
                           const LeafWeight& leafWeight) const {
  probability = 0;
  if (empty()) return -1;
  double chance = 1;
  Entry e = root_;
  BucketWeights kept[2];
  int keptIn = 0; // which of kept holds the weights of bucket e
  if (e < 0) weightOf(e, p, n, leafWeight, &kept[0]);
  while (e >= 0) {
    const Node& node = nodes_[static_cast<size_t>(e)];
    const double w0 = weightOf(node.child[0], p, n, leafWeight, &kept[0]);
    const double w1 = weightOf(node.child[1], p, n, leafWeight, &kept[1]);
    const double total = w0 + w1;
    if (!(total > 0)) return -1;
    const double p0 = w0 / total, p1 = w1 / total;
    // The first child below u (the second when rounding passes the first's share).
    const bool first = w0 > 0 && (u < p0 || !(w1 > 0));
    chance *= first ? p0 : p1;
    u = first ? u / p0 : (u - p0) / p1;
    u = std::clamp(u, 0.0, 1.0 - 0x1p-53);
    e = node.child[first ? 0 : 1];
    keptIn = first ? 0 : 1;
  }
  // Within the bucket, by its lights' weights (the last positive one if rounding passes it).
  const Bucket& b = buckets_[static_cast<size_t>(-(e + 1))];
  const BucketWeights& w = kept[keptIn];
  double total = 0;
  for (uint32_t i = 0; i < b.count; ++i) total += w[i];
  if (!(total > 0)) return -1;
  const double target = u * total;
  double below = 0;
  int slot = -1;
  for (uint32_t i = 0; i < b.count; ++i) {
    if (!(w[i] > 0)) continue;
    slot = static_cast<int>(i);
    if (target < below + w[i]) break;
    below += w[i];
  }
  if (target >= below + w[static_cast<size_t>(slot)]) below = total - w[static_cast<size_t>(slot)];
  u = std::clamp((target - below) / w[static_cast<size_t>(slot)], 0.0, 1.0 - 0x1p-53);
  probability = chance * (w[static_cast<size_t>(slot)] / total);
  return lights_[b.first + static_cast<uint32_t>(slot)];
}

template <class LeafWeight>
double SceneLightTree::probability(int k, const Vec3& p, const Vec3& n,
                                   const LeafWeight& leafWeight) const {
  if (!holds(k)) return 0;
  const Entry bucket = -(bucketOf_[static_cast<size_t>(k)] + 1);
  const Bucket& b = buckets_[static_cast<size_t>(bucketOf_[static_cast<size_t>(k)])];
  BucketWeights w;
  const double total = weightOf(bucket, p, n, leafWeight, &w);
  const double mine = w[slotOf_[static_cast<size_t>(k)]];
  if (!(mine > 0)) return 0;
  double chance = mine / total;
  int side = b.side;
  for (int32_t i = b.parent; i >= 0;) {
    const Node& node = nodes_[static_cast<size_t>(i)];
    const double w0 = weightOf(node.child[0], p, n, leafWeight, nullptr);
    const double w1 = weightOf(node.child[1], p, n, leafWeight, nullptr);
    const double here = side == 0 ? w0 : w1;
    if (!(here > 0)) return 0;
    chance *= here / (w0 + w1);
    side = side_[static_cast<size_t>(i)];
    i = parent_[static_cast<size_t>(i)];
  }
  return chance;
}

} // namespace nx
