#pragma once
// What a ray query returns: the nearest surface point with its frame and coordinates, and the
// box type the primitives give their bounds in (no Embree: the primitives fill hits).

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "accel/shape_kind.h"
#include "core/vec3.h"

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
  float u = 0, v = 0; ///< surface coordinates: each primitive's own (its file says which);
                      ///< 0 until surfaceUv() where the primitive defers them (spheres)
  ShapeKind kind = ShapeKind::Sphere;
  bool uvPending = false; ///< u and v are left for surfaceUv() (a primitive's lazy uv)
  uint32_t index = 0;     ///< index of the shape within its kind (sphere, plane, mesh)
  uint32_t prim = 0;      ///< triangle within the mesh; an analytic primitive's part; else 0
};

/// An axis-aligned box; empty when lo > hi.
struct BoundingBox {
  Vec3d lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  /// Grows the box to hold p.
  void add(const Vec3d& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  /// Grows the box to hold b.
  void add(const BoundingBox& b) {
    if (!b.empty()) add(b.lo), add(b.hi);
  }
  /// True if nothing was added.
  bool empty() const { return lo.x > hi.x; }
};

} // namespace nx
