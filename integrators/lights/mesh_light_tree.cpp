// The light BVH of an emitting mesh: build by the surface area orientation heuristic, walks
// down (choose) and up (probability).

#include "integrators/lights/mesh_light_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include "core/math_util.h"
#include "integrators/lights/light_tree_split.h"

namespace nx {
namespace {

// A binary light tree over triangles (a MeshLightTree before it is made 4-wide): nodes in
// depth-first order, each inner node's first child right after it.
struct BinaryTree {
  /// A triangle with what the build sorts and bounds it by.
  struct Primitive {
    LightBounds bounds;
    Vec3 centroid;
    Vec3d corner; ///< a corner (on the triangle's plane)
    uint32_t triangle;
  };
  std::vector<Primitive> prims;
  Vec3 anchor; ///< the planes' anchor tried first (LightBounds::planeAnchor)
  std::vector<LightBounds> bounds;
  std::vector<int32_t> second;   ///< inner nodes: the second child; leaves: -1
  std::vector<int32_t> triangle; ///< leaves: the triangle; inner nodes: -1

  /// Builds the node over prims[begin, end) at `depth`; returns its index.
  int32_t build(size_t begin, size_t end, int depth);
};

int32_t BinaryTree::build(size_t begin, size_t end, int depth) {
  const int32_t index = static_cast<int32_t>(bounds.size());
  bounds.emplace_back();
  second.push_back(-1);
  triangle.push_back(-1);
  // One pass over the node's triangles, given the mean of their normals (zero: none): the
  // spread of the normals about it, and the planes' least offset (LightBounds::planeOffset)
  // from the better of two anchors, the mesh's centroid (deep behind every plane of a convex
  // mesh) and the node's box centre.
  const auto finish = [&](LightBounds& b, const Vec3d& meanNormal) {
    const Vec3d fromBox(b.center()), fromCentroid(anchor);
    double spread = 1, leastBox = INFINITY, leastCentroid = INFINITY;
    for (size_t i = begin; i < end; ++i) {
      const Vec3d normal(prims[i].bounds.normals.axis);
      spread = std::min(spread, dot(meanNormal, normal));
      leastBox = std::min(leastBox, dot(normal, prims[i].corner - fromBox));
      leastCentroid = std::min(leastCentroid, dot(normal, prims[i].corner - fromCentroid));
    }
    b.planeAnchor = leastCentroid >= leastBox ? anchor : b.center();
    b.planeOffset = static_cast<float>(std::max(leastCentroid, leastBox));
    // The normals' cone from the normals themselves where it is tighter than the union of the
    // children's (which widens with every level: two quarter-sphere cones make a 140 degree
    // cone for a hemisphere's 90).
    const double cosSpread = spread - 1e-6; // rounded outward
    if (!(meanNormal == Vec3d()) && cosSpread > b.normals.cosSpread)
      b.normals = {Vec3(meanNormal), static_cast<float>(std::max(-1.0, cosSpread))};
  };
  if (end - begin == 1) {
    bounds[static_cast<size_t>(index)] = prims[begin].bounds;
    finish(bounds[static_cast<size_t>(index)], Vec3d());
    triangle[static_cast<size_t>(index)] = static_cast<int32_t>(prims[begin].triangle);
    return index;
  }
  LightBounds all, centroids; // boxes only
  Vec3d normalSum;            // area-weighted
  double area = 0;
  for (size_t i = begin; i < end; ++i) {
    all.add(prims[i].bounds.lo);
    all.add(prims[i].bounds.hi);
    centroids.add(prims[i].centroid);
    normalSum += Vec3d(prims[i].bounds.normals.axis) * static_cast<double>(prims[i].bounds.power);
    area += prims[i].bounds.power;
  }
  // The split of least cost Phi M_A M_Omega summed over both sides, times the box's longest
  // extent over its extent along the axis (Conty Estevez & Kulla's regularisation against
  // thin slabs), over kLightTreeBuckets buckets of centroids along each axis.
  size_t mid = begin;
  if (depth < kLightTreeHeuristicDepth) {
    const Vec3 extent = all.hi - all.lo;
    const float longest = std::max({extent.x, extent.y, extent.z});
    double bestCost = INFINITY;
    int bestAxis = -1, bestSplit = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const float lo = centroids.lo[axis], hi = centroids.hi[axis];
      if (!(hi > lo)) continue;
      // Each bucket's box, area, the area-weighted sum of its normals and its normals' cone
      // about their mean, spread to the farthest (dot products only: merging cone by cone
      // takes inverse cosines, most of the build's time).
      std::array<LightBounds, kLightTreeBuckets> buckets;
      std::array<Vec3d, kLightTreeBuckets> bucketNormalSum, meanNormal;
      std::array<double, kLightTreeBuckets> spread; // cos(theta_o) about the mean normal
      for (size_t i = begin; i < end; ++i) {
        const size_t k = static_cast<size_t>(lightTreeBucket(prims[i].centroid[axis], lo, hi));
        buckets[k].add(prims[i].bounds.lo);
        buckets[k].add(prims[i].bounds.hi);
        buckets[k].power += prims[i].bounds.power;
        bucketNormalSum[k] += Vec3d(prims[i].bounds.normals.axis) * double(prims[i].bounds.power);
      }
      for (size_t k = 0; k < kLightTreeBuckets; ++k) {
        const double l = length(bucketNormalSum[k]);
        meanNormal[k] = l > 0 ? bucketNormalSum[k] * (1 / l) : Vec3d(0, 0, 1);
        spread[k] = l > 1e-6 * buckets[k].power ? 1.0 : -1.0; // opposite normals: all
      }
      for (size_t i = begin; i < end; ++i) {
        const size_t k = static_cast<size_t>(lightTreeBucket(prims[i].centroid[axis], lo, hi));
        spread[k] = std::min(spread[k], dot(meanNormal[k], Vec3d(prims[i].bounds.normals.axis)));
      }
      // The cone of buckets [first, last) about their mean normal: each bucket's cone reaches
      // the angle to its mean plus its spread (cosines added, no inverse cosine).
      const auto sideOf = [&](size_t first, size_t last) {
        LightBounds side;
        Vec3d sum;
        for (size_t k = first; k < last; ++k) {
          if (!(buckets[k].power > 0)) continue;
          side.add(buckets[k].lo);
          side.add(buckets[k].hi);
          side.power += buckets[k].power;
          sum += bucketNormalSum[k];
        }
        const double l = length(sum);
        if (!(l > 1e-6 * side.power)) {
          side.normals = DirectionCone::all();
          return side;
        }
        const Vec3d mean = sum * (1 / l);
        double cosSpread = 1;
        for (size_t k = first; k < last; ++k) {
          if (!(buckets[k].power > 0)) continue;
          const double cosA = std::clamp(dot(mean, meanNormal[k]), -1.0, 1.0);
          const double sinA = std::sqrt(1 - cosA * cosA), cosB = spread[k];
          const double sinB = std::sqrt(std::max(0.0, 1 - cosB * cosB));
          // cos(a + b), or -1 where a + b passes pi (sin(a + b) < 0 with both in [0, pi]).
          const double sinSum = sinA * cosB + cosA * sinB;
          cosSpread = std::min(cosSpread, sinSum < 0 && cosA * cosB - sinA * sinB < 0
                                              ? -1.0
                                              : cosA * cosB - sinA * sinB);
        }
        side.normals = {Vec3(mean), static_cast<float>(cosSpread - 1e-6)};
        return side;
      };
      const double regular = extent[axis] > 0 ? longest / extent[axis] : 1.0;
      for (int split = 1; split < kLightTreeBuckets; ++split) {
        const LightBounds below = sideOf(0, static_cast<size_t>(split));
        const LightBounds above = sideOf(static_cast<size_t>(split), kLightTreeBuckets);
        if (!(below.power > 0) || !(above.power > 0)) continue;
        const double cost =
            regular *
            (below.power * surfaceArea(below) * orientationMeasure(below.normals.cosSpread, 0) +
             above.power * surfaceArea(above) * orientationMeasure(above.normals.cosSpread, 0));
        if (cost < bestCost) bestCost = cost, bestAxis = axis, bestSplit = split;
      }
    }
    if (bestAxis >= 0) {
      const float lo = centroids.lo[bestAxis], hi = centroids.hi[bestAxis];
      const auto split =
          std::partition(prims.begin() + static_cast<std::ptrdiff_t>(begin),
                         prims.begin() + static_cast<std::ptrdiff_t>(end), [&](const Primitive& p) {
                           return lightTreeBucket(p.centroid[bestAxis], lo, hi) < bestSplit;
                         });
      mid = static_cast<size_t>(split - prims.begin());
    }
  }
  if (mid <= begin || mid >= end) {
    // No useful split (coincident centroids, or deep): halves along the longest axis.
    mid =
        splitAtMedian(prims, begin, end, centroids, [](const Primitive& p) { return p.centroid; });
  }
  build(begin, mid, depth + 1);
  const int32_t other = build(mid, end, depth + 1);
  second[static_cast<size_t>(index)] = other;
  LightBounds& node = bounds[static_cast<size_t>(index)];
  node = unionOf(bounds[static_cast<size_t>(index) + 1], bounds[static_cast<size_t>(other)]);
  const double sumLength = length(normalSum);
  finish(node, sumLength > 1e-6 * area ? normalSum * (1 / sumLength) : Vec3d());
  return index;
}

} // namespace

MeshLightTree::MeshLightTree(const TriangleMesh& mesh, int outwardSign)
    : closed_(outwardSign != 0) {
  BinaryTree binary;
  std::vector<BinaryTree::Primitive>& prims = binary.prims;
  prims.reserve(mesh.triangleCount());
  leafNode_.assign(mesh.triangleCount(), -1);
  leafSlot_.assign(mesh.triangleCount(), 0);
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const TriangleShape c = mesh.corners(t);
    const Vec3d nd = cross(c.b - c.a, c.c - c.a);
    const double len = length(nd);
    if (!(len > 0) || !std::isfinite(len)) continue;
    BinaryTree::Primitive p;
    p.bounds.add(Vec3(c.a));
    p.bounds.add(Vec3(c.b));
    p.bounds.add(Vec3(c.c));
    p.bounds.normals = {Vec3(nd * ((outwardSign < 0 ? -1.0 : 1.0) / len)), 1.0f};
    p.bounds.power = static_cast<float>(0.5 * len);
    p.centroid = Vec3((c.a + c.b + c.c) * (1.0 / 3));
    p.corner = c.a;
    p.triangle = static_cast<uint32_t>(t);
    prims.push_back(p);
  }
  if (prims.empty()) return;
  // The centroid of the enclosed volume (of the surface for an open mesh).
  Vec3d weighted, areaWeighted;
  double volume = 0, area = 0;
  for (const BinaryTree::Primitive& p : prims) {
    const TriangleShape c = mesh.corners(p.triangle);
    const double v = dot(c.a, cross(c.b, c.c)) / 6;
    weighted += (c.a + c.b + c.c) * (v / 4);
    volume += v;
    areaWeighted += Vec3d(p.centroid) * static_cast<double>(p.bounds.power);
    area += p.bounds.power;
  }
  binary.anchor =
      Vec3(closed_ && volume != 0 ? weighted * (1 / volume) : areaWeighted * (1 / area));
  binary.bounds.reserve(2 * prims.size() - 1);
  binary.build(0, prims.size(), 0);
  root_ = LightCluster(binary.bounds.front());
  boxLo_ = binary.bounds.front().lo;
  boxHi_ = binary.bounds.front().hi;

  // Made 4-wide: a wide node's lanes are its binary node's grandchildren (or a child that is
  // a leaf); a triangle alone is a root of one lane.
  struct Pending {
    int32_t binary, parent;
    uint8_t slot;
    int depth;
  };
  std::vector<Pending> pending{{0, -1, 0, 1}};
  while (!pending.empty()) {
    const Pending at = pending.back();
    pending.pop_back();
    const int32_t index = static_cast<int32_t>(nodes_.size());
    if (at.parent >= 0) nodes_[static_cast<size_t>(at.parent)].child[at.slot] = index;
    parent_.push_back(at.parent);
    slotInParent_.push_back(at.slot);
    depth_ = std::max(depth_, at.depth);
    int32_t lanes[kWidth];
    int count = 0;
    const auto inner = [&](int32_t b) { return binary.second[static_cast<size_t>(b)] >= 0; };
    if (!inner(at.binary)) {
      lanes[count++] = at.binary;
    } else {
      for (const int32_t c : {at.binary + 1, binary.second[static_cast<size_t>(at.binary)]}) {
        if (!inner(c)) {
          lanes[count++] = c;
        } else {
          lanes[count++] = c + 1;
          lanes[count++] = binary.second[static_cast<size_t>(c)];
        }
      }
    }
    WideNode node{};
    for (int k = 0; k < kWidth; ++k) {
      node.child[k] = kNoChild;
      node.planeOffset[k] = -INFINITY;
      if (k >= count) continue; // an empty lane: power 0, never chosen
      const LightCluster c(binary.bounds[static_cast<size_t>(lanes[k])]);
      node.cx[k] = c.center.x, node.cy[k] = c.center.y, node.cz[k] = c.center.z;
      node.radius[k] = c.radius;
      node.ax[k] = c.axis.x, node.ay[k] = c.axis.y, node.az[k] = c.axis.z;
      node.cosSpread[k] = c.cosSpread, node.sinSpread[k] = c.sinSpread;
      node.power[k] = c.power;
      node.anchorX[k] = c.planeAnchor.x, node.anchorY[k] = c.planeAnchor.y;
      node.anchorZ[k] = c.planeAnchor.z, node.planeOffset[k] = c.planeOffset;
      const int32_t t = binary.triangle[static_cast<size_t>(lanes[k])];
      if (t >= 0) {
        node.child[k] = -(t + 1);
        leafNode_[static_cast<size_t>(t)] = index;
        leafSlot_[static_cast<size_t>(t)] = static_cast<uint8_t>(k);
      } else {
        pending.push_back({lanes[k], index, static_cast<uint8_t>(k), at.depth + 1});
      }
    }
    nodes_.push_back(node);
  }
}

bool MeshLightTree::oneSidedAt(const Vec3& p) const {
  return closed_ && (p.x < boxLo_.x || p.y < boxLo_.y || p.z < boxLo_.z || p.x > boxHi_.x ||
                     p.y > boxHi_.y || p.z > boxHi_.z);
}

namespace {

// Four floats weighed together (GCC/Clang vector extensions: SSE on x86, plain code elsewhere).
typedef float Lanes __attribute__((vector_size(16)));
typedef int32_t LaneMask __attribute__((vector_size(16)));

Lanes lanesOf(const float (&a)[4]) {
  Lanes v;
  std::memcpy(&v, a, sizeof v);
  return v;
}
// Per lane: mask ? a : b.
Lanes select(LaneMask mask, Lanes a, Lanes b) {
  return reinterpret_cast<Lanes>((reinterpret_cast<LaneMask>(a) & mask) |
                                 (reinterpret_cast<LaneMask>(b) & ~mask));
}
Lanes lanesMax(Lanes a, Lanes b) {
  return select(a > b, a, b);
}
Lanes lanesMin(Lanes a, Lanes b) {
  return select(a < b, a, b);
}
Lanes lanesSqrt(Lanes x) {
#if defined(__SSE__)
  return reinterpret_cast<Lanes>(_mm_sqrt_ps(reinterpret_cast<__m128>(x)));
#else
  for (int k = 0; k < 4; ++k) x[k] = std::sqrt(x[k]);
  return x;
#endif
}

} // namespace

void MeshLightTree::weigh(const WideNode& node, const Vec3& p, const Vec3& n, bool twoSided,
                          float (&w)[kWidth]) {
  // LightCluster::importance and behindAllPlanes on the four lanes at once; each choice a
  // per-lane select.
  static_assert(kWidth == 4);
  const Lanes zero = {0, 0, 0, 0}, one = {1, 1, 1, 1};
  const Lanes tx = p.x - lanesOf(node.cx), ty = p.y - lanesOf(node.cy), tz = p.z - lanesOf(node.cz);
  const Lanes radius = lanesOf(node.radius), ax = lanesOf(node.ax), ay = lanesOf(node.ay),
              az = lanesOf(node.az), cosO = lanesOf(node.cosSpread), sinO = lanesOf(node.sinSpread),
              power = lanesOf(node.power);
  const Lanes d2 = tx * tx + ty * ty + tz * tz, r2 = radius * radius;
  const Lanes rawAlong = ax * tx + ay * ty + az * tz;
  // |along| when both faces emit.
  const Lanes along = twoSided ? lanesMax(rawAlong, -rawAlong) : rawAlong;
  const Lanes rawAcross = n.x * tx + n.y * ty + n.z * tz;
  const Lanes across = lanesMax(rawAcross, -rawAcross);
  const Lanes invD = one / lanesSqrt(d2);
  const Lanes sinU = radius * invD;
  const Lanes cosU = lanesSqrt(lanesMax(zero, d2 - r2)) * invD;
  const Lanes cosPsi = cosO * cosU - sinO * sinU, sinPsi = sinO * cosU + cosO * sinU;
  const Lanes cosTheta = lanesMin(one, along * invD);
  const Lanes sinTheta = lanesSqrt(lanesMax(zero, d2 - rawAlong * rawAlong)) * invD;
  const Lanes cosPrime =
      select((sinPsi >= zero) & (cosTheta < cosPsi), cosTheta * cosPsi + sinTheta * sinPsi, one);
  Lanes outside = power * lanesMax(zero, cosPrime) * invD * invD;
  if (!(n == Vec3())) {
    const Lanes cosI = lanesMin(one, across * invD);
    const Lanes sinI = lanesSqrt(lanesMax(zero, d2 - across * across)) * invD;
    outside = outside * select(cosI < cosU, cosI * cosU + sinI * sinU, one);
  }
  const Lanes inside = power / lanesMax(lanesMax(r2, d2), Lanes{1e-30f, 1e-30f, 1e-30f, 1e-30f});
  Lanes value = select(d2 > r2, outside, inside);
  if (!twoSided) {
    // The planes' test: the largest dot(m, p - anchor) over the cone against the offset.
    const Lanes qx = p.x - lanesOf(node.anchorX), qy = p.y - lanesOf(node.anchorY),
                qz = p.z - lanesOf(node.anchorZ);
    const Lanes q2 = qx * qx + qy * qy + qz * qz, qa = ax * qx + ay * qy + az * qz;
    const Lanes qLength = lanesSqrt(q2), qAcross = lanesSqrt(lanesMax(zero, q2 - qa * qa));
    const Lanes reach = select(qa >= qLength * cosO, qLength, qa * cosO + qAcross * sinO);
    const Lanes offset = lanesOf(node.planeOffset);
    const Lanes margin = 1e-5f * (qLength + lanesMax(offset, -offset));
    value = select(reach + margin <= offset, zero, value);
  }
  // Zero (not NaN) for empty lanes and whatever else is not a positive weight.
  value = select(value > zero, value, zero);
  std::memcpy(w, &value, sizeof value);
}

int MeshLightTree::choose(const Vec3& p, const Vec3& n, double u, double& probability) const {
  probability = 0;
  if (nodes_.empty()) return -1;
  const bool twoSided = !oneSidedAt(p);
  double chance = 1;
  for (int32_t i = 0;;) {
    const WideNode& node = nodes_[static_cast<size_t>(i)];
    float w[kWidth];
    weigh(node, p, n, twoSided, w);
    double total = 0;
    for (const float x : w) total += x;
    if (!(total > 0)) return -1;
    // The lane whose share of the total holds u (the last positive one if rounding passes it).
    const double target = u * total;
    double below = 0;
    int lane = -1;
    for (int k = 0; k < kWidth; ++k) {
      if (!(w[k] > 0)) continue;
      lane = k;
      if (target < below + w[k]) break;
      below += w[k];
    }
    if (target >= below + w[lane]) below = total - w[lane];
    u = std::clamp((target - below) / w[lane], 0.0, 1.0 - 0x1p-53);
    chance *= w[lane] / total;
    const int32_t child = node.child[lane];
    if (child < 0) {
      probability = chance;
      return -(child + 1);
    }
    i = child;
  }
}

double MeshLightTree::probability(uint32_t t, const Vec3& p, const Vec3& n) const {
  if (t >= leafNode_.size() || leafNode_[t] < 0) return 0;
  const bool twoSided = !oneSidedAt(p);
  double chance = 1;
  int slot = leafSlot_[t];
  for (int32_t i = leafNode_[t]; i >= 0;) {
    float w[kWidth];
    weigh(nodes_[static_cast<size_t>(i)], p, n, twoSided, w);
    double total = 0;
    for (const float x : w) total += x;
    if (!(w[slot] > 0)) return 0;
    chance *= w[slot] / total;
    slot = slotInParent_[static_cast<size_t>(i)];
    i = parent_[static_cast<size_t>(i)];
  }
  return chance;
}

} // namespace nx
