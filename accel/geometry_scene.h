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

#include "accel/shape_kind.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <vector>

#include "accel/embree_device.h"
#include "accel/kinds/cylinder.h"
#include "accel/kinds/disk.h"
#include "accel/shapes.h"
#include "core/ray.h"
#include "core/triangle_mesh.h"

namespace nx {

/// The nearest surface a ray meets.
struct SurfaceHit {
  float t = 0;        ///< ray parameter
  Vec3 p;             ///< hit point
  Vec3 pError;        ///< bound on |p - true surface point| per component
  Vec3 ng;            ///< unit geometric normal (outward for spheres; the plane's normal;
                      ///< (b - a) x (c - a) for triangles), not flipped towards the ray
  Vec3 ns;            ///< unit shading normal: interpolated vertex normals on meshes that have them
                      ///< (on the side of ng), else ng
  Vec3 dpdu;          ///< surface tangent along u (not unit; orthogonal to nothing in particular)
  float u = 0, v = 0; ///< surface coordinates: mesh uv (or barycentrics mapped to (0,0),
                      ///< (1,0), (1,1)); spheres: 0 until sphereUv(); planes: 0; disks and
                      ///< cylinders: their polar or cylindrical coordinates
  ShapeKind kind = ShapeKind::Sphere;
  uint32_t index = 0; ///< index of the shape within its kind (sphere, plane, mesh)
  uint32_t prim = 0;  ///< triangle within the mesh; a cylinder's part (CylinderPart); else 0
};

/// Fills a sphere hit's (u, v) = (phi / 2 pi, theta / pi), phi around +y from +z towards +x
/// and theta from +y; left out of intersect() so that untextured spheres do not pay for it.
void sphereUv(SurfaceHit& hit);

/// An axis-aligned box; empty when lo > hi.
struct BoundingBox {
  Vec3d lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  /// Grows the box to hold p.
  void add(const Vec3d& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  /// True if nothing was added.
  bool empty() const { return lo.x > hi.x; }
};

/// The geometry of a scene, ready for ray queries from any number of threads.
class GeometryScene {
public:
  /// Builds the BVH over spheres and meshes; planes are kept for the analytic pass. Meshes must
  /// be valid (TriangleMesh::validate()).
  GeometryScene(EmbreeDevice& device, std::vector<SphereShape> spheres,
                std::vector<PlaneShape> planes, std::vector<TriangleMesh> meshes,
                std::vector<DiskShape> disks = {}, std::vector<CylinderShape> cylinders = {});
  ~GeometryScene();
  GeometryScene(const GeometryScene&) = delete;
  GeometryScene& operator=(const GeometryScene&) = delete;

  /// Nearest hit of `ray` in (ray.tMin, ray.tMax), or false.
  bool intersect(const Ray& ray, SurfaceHit& hit) const;
  /// True if anything blocks `ray` in (ray.tMin, ray.tMax).
  bool occluded(const Ray& ray) const;

  /// Number of hits discarded because their point or normal was not finite (should be 0).
  uint64_t nonFiniteHits() const { return nonFinite_.load(std::memory_order_relaxed); }

  const std::vector<SphereShape>& spheres() const { return spheres_; }
  const std::vector<PlaneShape>& planes() const { return planes_; }
  const std::vector<TriangleMesh>& meshes() const { return meshes_; }
  const std::vector<DiskShape>& disks() const { return disks_; }
  const std::vector<CylinderShape>& cylinders() const { return cylinders_; }
  /// Bounds of the bounded shapes (planes are unbounded).
  BoundingBox bounds() const;
  /// The Embree scene of the spheres and meshes (not the planes), for benchmarks that query it
  /// directly.
  RTCScene embreeScene() const { return scene_; }
  /// Bytes Embree's BVH and buffers take beyond the meshes' own (from its memory monitor).
  size_t embreeBytes() const { return embreeBytes_; }

private:
  std::vector<SphereShape> spheres_;
  std::vector<PlaneShape> planes_;
  std::vector<TriangleMesh> meshes_;
  std::vector<DiskShape> disks_;
  std::vector<CylinderShape> cylinders_;
  RTCScene scene_ = nullptr;
  /// The primitive table: what each Embree geometry id is (sphere set or mesh number).
  struct GeometryEntry {
    ShapeKind kind;
    uint32_t mesh;
  };
  std::vector<GeometryEntry> byGeomId_;
  size_t embreeBytes_ = 0;
  void fillMeshHit(float baryU, float baryV, const Vec3& ngEmbree, SurfaceHit& hit) const;
  void fillDiskHit(const Vec3d& o, const Vec3d& d, SurfaceHit& hit) const;
  void fillCylinderHit(const Vec3d& o, const Vec3d& d, CylinderPart part, SurfaceHit& hit) const;
  mutable std::atomic<uint64_t> nonFinite_{0};
};

} // namespace nx
