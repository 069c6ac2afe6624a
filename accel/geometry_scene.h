#pragma once
// The scene's geometry in Embree: spheres as user geometry, each triangle mesh as one Embree
// triangle geometry reading the mesh's own buffers, and infinite planes intersected
// analytically after the BVH query.
//
// Why planes are not in the BVH: Embree silently drops primitives with bounds beyond about
// 1.8e18, and huge finite bounds make every BVH node around them useless (measured here: +20%
// time with 8 spheres, 2.5x with 100,000). A scene has a handful of planes, so one exact
// ray/plane test each outside the BVH costs little and renders them correctly to the horizon. The
// planes are tested first, so their nearest hit bounds the BVH query.

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <vector>

#include "accel/embree_device.h"
#include "accel/shape_kinds.h"
#include "accel/surface_hit.h"
#include "core/ray.h"
#include "core/triangle_mesh.h"

namespace nx {

/// The geometry of a scene, ready for ray queries from any number of threads.
class GeometryScene {
public:
  /// Builds the BVH over the analytic primitives and meshes; planes are kept for the analytic
  /// pass. Meshes must be valid (TriangleMesh::validate()).
  GeometryScene(EmbreeDevice& device, AnalyticShapes analytic, std::vector<PlaneShape> planes,
                std::vector<TriangleMesh> meshes);
  /// A scene of spheres, planes and meshes only.
  GeometryScene(EmbreeDevice& device, std::vector<SphereShape> spheres,
                std::vector<PlaneShape> planes, std::vector<TriangleMesh> meshes);
  ~GeometryScene();
  GeometryScene(const GeometryScene&) = delete;
  GeometryScene& operator=(const GeometryScene&) = delete;

  /// Nearest hit of `ray` in (ray.tMin, ray.tMax), or false.
  bool intersect(const Ray& ray, SurfaceHit& hit) const;
  /// True if anything blocks `ray` in (ray.tMin, ray.tMax).
  bool occluded(const Ray& ray) const;

  /// Number of hits discarded because their point or normal was not finite (should be 0).
  uint64_t nonFiniteHits() const { return nonFinite_.load(std::memory_order_relaxed); }

  /// The analytic primitives of type P, in the order the scene gave them (hit.index).
  template <class P>
  const std::vector<P>& primitives() const {
    return std::get<std::vector<P>>(analytic_);
  }
  /// All analytic primitives, one vector per type.
  const AnalyticShapes& analytic() const { return analytic_; }
  /// visit(p) for analytic primitive `index` of `kind` (isAnalytic(kind)).
  template <class Visit>
  decltype(auto) visitPrimitive(ShapeKind kind, uint32_t index, Visit&& visit) const {
    return visitAnalyticKind(
        kind, [&]<class P>() -> decltype(auto) { return visit(primitives<P>()[index]); });
  }
  /// How many primitives of analytic `kind` the scene holds.
  size_t primitiveCount(ShapeKind kind) const {
    return visitAnalyticKind(kind, [&]<class P>() { return primitives<P>().size(); });
  }
  const std::vector<SphereShape>& spheres() const { return primitives<SphereShape>(); }
  const std::vector<PlaneShape>& planes() const { return planes_; }
  const std::vector<TriangleMesh>& meshes() const { return meshes_; }
  /// Bounds of the bounded shapes (planes are unbounded).
  BoundingBox bounds() const;
  /// The Embree scene of the spheres and meshes (not the planes), for benchmarks that query it
  /// directly.
  RTCScene embreeScene() const { return scene_; }
  /// Bytes Embree's BVH and buffers take beyond the meshes' own (from its memory monitor).
  size_t embreeBytes() const { return embreeBytes_; }

private:
  AnalyticShapes analytic_;
  std::vector<PlaneShape> planes_;
  std::vector<TriangleMesh> meshes_;
  RTCScene scene_ = nullptr;
  /// The primitive table: what each Embree geometry id is (an analytic kind's set or a mesh).
  struct GeometryEntry {
    ShapeKind kind;
    uint32_t mesh;
  };
  std::vector<GeometryEntry> byGeomId_;
  size_t embreeBytes_ = 0;
  void fillMeshHit(float baryU, float baryV, const Vec3& ngEmbree, SurfaceHit& hit) const;
  mutable std::atomic<uint64_t> nonFinite_{0};
};

} // namespace nx
