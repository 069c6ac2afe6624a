#pragma once
// What next-event estimation draws from a light: a direction, the point it ends at and what
// arrives along it.

#include <cstdint>

#include "accel/shape_kind.h"
#include "core/ray.h"
#include "spectra/sampled_wavelengths.h"

namespace nx {

/// The kinds of light next-event estimation can aim at.
enum class LightKind : uint8_t {
  Point,       ///< a light of the scene's <light> list: a point or spot light (a delta, never
               ///< hit by BSDF sampling)
  Cone,        ///< an emitting analytic primitive that samples the solid angle it subtends
               ///< (a sphere: its cone from outside, uniform from inside)
  Mesh,        ///< an emitting mesh or inline triangle (sampled by solid angle or by area:
               ///< TriangleLightSampling)
  Area,        ///< an emitting analytic primitive sampled by area (a disk, a cylinder, ...)
  Background,  ///< the uniform environment (uniform directions)
  Environment, ///< an infinite light of the scene's <light> list (an environment map: its
               ///< kind samples it)
};

/// A direction towards a light, with what arrives along it.
struct LightSample {
  Vec3 wi;                  ///< unit direction from the shading point
  float distance = 0;       ///< to the light's point (infinity for the background)
  Vec3 p;                   ///< the point on the light (its position for point lights)
  Vec3 pError;              ///< bound on |p - true surface point| per component
  Vec3 n;                   ///< the light's geometric normal at p (zero for point lights)
  SampledSpectrum radiance; ///< emitted radiance (area lights) or I / d^2 (point lights)
  float pdf = 0; ///< solid-angle density including the light choice; for point lights the choice
                 ///< probability
  bool delta = false;                ///< a point light: cannot be hit by BSDF sampling
  bool infinite = false;             ///< the background: the shadow ray has no end
  ShapeKind kind = ShapeKind::Plane; ///< the shape the point lies on (shape lights only)
  uint32_t shape = 0, prim = 0;      ///< its index within its kind, and triangle
  int32_t light = -1;                ///< the light's number in its LightSampler
};

/// Shadow rays end this fraction short of the light's offset point (pbrt-v4's ShadowEpsilon):
/// both ends are already moved off their surfaces by their error bounds, the margin only
/// absorbs the rounding of the direction.
inline constexpr float kShadowEpsilon = 1e-4f;

/// The shadow ray from surface point (p, pError, n) to the light sample: origin and end both
/// moved off their surfaces by their error bounds, towards each other (pbrt-v4's SpawnRayTo);
/// the direction is not unit length and the ray is valid for t in (0, 1 - kShadowEpsilon). A
/// background sample gives a unit direction valid to infinity.
Ray shadowRayTo(const Vec3& p, const Vec3& pError, const Vec3& n, const LightSample& ls);

} // namespace nx
