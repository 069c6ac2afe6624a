#pragma once
// The scene's geometry in Embree: spheres as user geometry, triangles as Embree triangles,
// and infinite planes intersected analytically after the BVH query.
//
// Why planes are not in the BVH: Embree silently drops primitives with bounds beyond about
// 1.8e18, and huge finite bounds make every BVH node around them useless (measured here: +20%
// time with 8 spheres, 2.5x with 100,000). A scene has a handful of planes, so one exact
// ray/plane test each outside the BVH costs little and renders them correctly to the horizon. The
// planes are tested first, so their nearest hit bounds the BVH query.

#include <embree3/rtcore.h>

#include <atomic>
#include <cstdint>
#include <vector>

#include "accel/embree_device.h"
#include "accel/shapes.h"
#include "core/ray.h"

namespace nx {

/// Which kind of shape a hit is on.
enum class ShapeKind : uint8_t { Sphere, Plane, Triangle };

/// The nearest surface a ray meets.
struct SurfaceHit {
  float t = 0; ///< ray parameter
  Vec3 p;      ///< hit point
  Vec3 pError; ///< bound on |p - true surface point| per component
  Vec3 ng;     ///< unit geometric normal (outward for spheres; the plane's normal;
               ///< (b - a) x (c - a) for triangles), not flipped towards the ray
  ShapeKind kind = ShapeKind::Sphere;
  uint32_t index = 0; ///< index of the shape within its kind
};

/// The geometry of a scene, ready for ray queries from any number of threads.
class GeometryScene {
public:
  /// Builds the BVH over spheres and triangles; planes are kept for the analytic pass.
  GeometryScene(EmbreeDevice& device, std::vector<SphereShape> spheres,
                std::vector<PlaneShape> planes, std::vector<TriangleShape> triangles);
  ~GeometryScene();
  GeometryScene(const GeometryScene&) = delete;
  GeometryScene& operator=(const GeometryScene&) = delete;

  /// Nearest hit of `ray` in (ray.tMin, ray.tMax), or false.
  bool intersect(const Ray& ray, SurfaceHit& hit) const;
  /// Sphere index meaning "no sphere" for occluded().
  static constexpr uint32_t kNoSphere = 0xffffffffu;
  /// True if anything blocks `ray` in (ray.tMin, ray.tMax). Sphere `ignoredSphere` is not
  /// tested: a shadow ray towards a sphere light ends before that sphere's surface, where the
  /// sphere cannot block it, so its test would only cost time.
  bool occluded(const Ray& ray, uint32_t ignoredSphere = kNoSphere) const;

  /// Number of hits discarded because their point or normal was not finite (should be 0).
  uint64_t nonFiniteHits() const { return nonFinite_.load(std::memory_order_relaxed); }

  const std::vector<SphereShape>& spheres() const { return spheres_; }
  const std::vector<PlaneShape>& planes() const { return planes_; }
  const std::vector<TriangleShape>& triangles() const { return triangles_; }

private:
  std::vector<SphereShape> spheres_;
  std::vector<PlaneShape> planes_;
  std::vector<TriangleShape> triangles_;
  RTCScene scene_ = nullptr;
  unsigned sphereGeomId_ = RTC_INVALID_GEOMETRY_ID;
  unsigned triangleGeomId_ = RTC_INVALID_GEOMETRY_ID;
  mutable std::atomic<uint64_t> nonFinite_{0};
};

} // namespace nx
