#pragma once
// A light BVH over the triangles of one emitting mesh: next-event estimation walks it from the
// root, choosing each child in proportion to the light it can send to the shading point
// (LightCluster::importance), so triangles turned away or far away are rarely or never chosen
// (Conty Estevez & Kulla 2018; pbrt-v4 builds one over all of a scene's lights).

#include <cstdint>
#include <vector>

#include "core/triangle_mesh.h"
#include "integrators/lights/light_bounds.h"

namespace nx {

/// Meshes of more triangles than this get a MeshLightTree (smaller ones choose their triangle
/// by solid angle, LightSampler).
inline constexpr size_t kMeshLightTreeFrom = 4;

/// The light BVH of an emitting mesh, built binary by the surface area orientation heuristic
/// and walked as a 4-wide tree (each level weighs four clusters at once). A closed,
/// consistently wound mesh (MeshClosure) seen from outside its bounding box can only show the
/// outer face of each triangle: there the normals are taken outward and clusters behind every
/// plane of their triangles are never chosen; elsewhere, and for open meshes, each triangle
/// emits from both faces.
class MeshLightTree {
public:
  /// The tree over mesh's triangles of positive area. outwardSign: +1 or -1 for a closed mesh
  /// (the sign that turns (b - a) x (c - a) outward), 0 for an open one.
  MeshLightTree(const TriangleMesh& mesh, int outwardSign);

  /// True when no triangle has an area.
  bool empty() const { return nodes_.empty(); }
  /// Bounds of the whole mesh (power: its area; normals outward for a closed mesh).
  const LightCluster& bounds() const { return root_; }
  /// Whether the mesh is closed (its outer faces alone are seen from outside).
  bool closed() const { return closed_; }
  /// Whether only outer faces can be seen from p: a closed mesh and p outside its box.
  bool oneSidedAt(const Vec3& p) const;
  /// Importance of the whole mesh at (p, n) (LightCluster::importance, area as power); seen
  /// from outside, a closed mesh shows on average a quarter of its area (Cauchy's formula for
  /// convex bodies, at most that for any closed surface), so its area counts a quarter there.
  float importance(const Vec3& p, const Vec3& n) const {
    return oneSidedAt(p) ? 0.25f * root_.importance(p, n, false) : root_.importance(p, n, true);
  }

  /// A triangle chosen by walking down from the root with u in [0, 1), each child in proportion
  /// to its importance at (p, n) (n zero: no receiver), and the probability of that choice;
  /// -1 when nothing can light p (also where a cluster's bound was positive but none of its
  /// children's is: no sample, which the probabilities account for).
  int choose(const Vec3& p, const Vec3& n, double u, double& probability) const;
  /// The probability with which choose() returns triangle t at (p, n) (0 when it never does).
  double probability(uint32_t t, const Vec3& p, const Vec3& n) const;

  /// Number of 4-wide nodes.
  size_t nodeCount() const { return nodes_.size(); }
  /// Levels of 4-wide nodes above the deepest triangle (one triangle alone: 1).
  int depth() const { return depth_; }

private:
  static constexpr int kWidth = 4;
  /// Up to kWidth clusters, their LightCluster fields lane by lane (weighed together).
  struct alignas(64) WideNode {
    float cx[kWidth], cy[kWidth], cz[kWidth], radius[kWidth];
    float ax[kWidth], ay[kWidth], az[kWidth], cosSpread[kWidth];
    float sinSpread[kWidth], power[kWidth], anchorX[kWidth], anchorY[kWidth];
    float anchorZ[kWidth], planeOffset[kWidth];
    int32_t child[kWidth]; ///< a wide node (>= 0), triangle t as -(t + 1), or kNoChild
  };
  static constexpr int32_t kNoChild = INT32_MIN;
  /// The importance of node's clusters at (p, n) (LightCluster::importance lane by lane).
  static void weigh(const WideNode& node, const Vec3& p, const Vec3& n, bool twoSided,
                    float (&w)[kWidth]);

  std::vector<WideNode> nodes_;
  std::vector<int32_t> parent_;       ///< per node: its parent, -1 for the root
  std::vector<uint8_t> slotInParent_; ///< per node: its lane in its parent
  std::vector<int32_t> leafNode_;     ///< per triangle: the node holding it, or -1 (no area)
  std::vector<uint8_t> leafSlot_;     ///< per triangle: its lane there
  LightCluster root_;
  bool closed_ = false;
  Vec3 boxLo_, boxHi_;
  int depth_ = 0;
};

} // namespace nx
