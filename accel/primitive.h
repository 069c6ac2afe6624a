#pragma once
// What an analytic primitive (a sphere, a disk, a cylinder, a capsule: Embree user geometry)
// owns, so that the geometry, the light sampler, the measured emitter and the gradient code
// ask it instead of branching on its kind. A primitive is a struct in its kind's header
// (accel/kinds/) that satisfies AnalyticPrimitive; the list NX_ANALYTIC_PRIMITIVES
// (accel/shape_kind.h) registers it, and everything else is generated from that list.

#include <cmath>
#include <concepts>
#include <optional>
#include <string>
#include <utility>

#include "accel/surface_hit.h"
#include "core/math_util.h"
#include "core/sampler.h"
#include "core/vec3.h"

namespace nx {

/// Where a ray meets a primitive: its parameter and which part of the primitive it is on (a
/// cylinder's side or cap; 0 for one-part primitives).
struct PrimitiveHit {
  double t;
  uint32_t part = 0;
};

/// A point drawn on a primitive's surface uniformly by area: the point, its unit normal
/// (outward; a disk's front) and which part of the primitive it is on.
struct AreaSample {
  Vec3d p, n;
  uint32_t part = 0;
};

/// A direction drawn towards a primitive by the solid angle it subtends, where it has such a
/// sampling (a sphere's cone): the unit direction, the distance to the point it reaches, that
/// point and its unit normal (on the surface, in double), and the density in solid angle.
struct SolidAngleSample {
  Vec3 wi;
  double distance = 0;
  Vec3d p, n;
  double pdf = 0;
  uint32_t part = 0;
};

/// An orthonormal frame in double around a unit axis n (Duff et al., "Building an Orthonormal
/// Basis, Revisited", JCGT 2017): s, t and n, right-handed.
struct AxisFrame {
  Vec3d s, t, n;
  /// The frame of unit axis n.
  static AxisFrame of(const Vec3d& n) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z), b = n.x * n.y * a;
    return {Vec3d(1 + sign * n.x * n.x * a, sign * b, -sign * n.x),
            Vec3d(b, sign + n.y * n.y * a, -n.y), n};
  }
};

/// phi / 2 pi in [0, 1) of the angle atan2(y, x): the u of polar and cylindrical coordinates.
inline float turnFraction(double y, double x) {
  const double phi = std::atan2(y, x);
  return static_cast<float>((phi < 0 ? phi + 2 * kPi : phi) / (2 * kPi));
}

/// Whether the light a primitive sends can fall on another point of the same primitive, for
/// next-event estimation: never (flat), only from its inside (closed and convex), or possibly
/// anywhere (open or not convex: the shadow ray tells).
enum class SelfLighting { Never, FromInside, Possible };

/// A primitive that samples the solid angle it subtends from a point (the light sampler then
/// prefers it to area sampling): sampleSolidAngle(p, u) gives a direction that reaches it (or
/// nothing), solidAnglePdf(p, wi) its density, and boundingSphere() the sphere whose cone
/// bounds what it subtends (for the lights' selection weights).
template <class P>
concept SamplesSolidAngle = requires(const P& s, const Vec3& p, Sample2 u) {
  { s.sampleSolidAngle(p, u) } -> std::same_as<std::optional<SolidAngleSample>>;
  { s.solidAnglePdf(p, p) } -> std::same_as<double>;
  { s.boundingSphere() } -> std::same_as<std::pair<Vec3d, double>>;
};

/// What the geometry and the renderer ask of an analytic primitive. Each member is the
/// primitive's own; none has a default, so a new primitive that leaves one out is a compile
/// error where it is registered.
template <class P>
concept AnalyticPrimitive = requires(const P& p, const Vec3d& v, double x, uint32_t part,
                                     SurfaceHit& hit, Sample2 u, const std::string& where) {
  /// Its axis-aligned bounds.
  { p.bounds() } -> std::same_as<BoundingBox>;
  /// The nearest hit of o + t d with t in (tMin, tMax) (d need not be unit length).
  { p.intersect(v, v, x, x) } -> std::same_as<std::optional<PrimitiveHit>>;
  /// The surface at a hit (point projected onto the surface in double, its error bound,
  /// normals, uv or uvPending, dp/du), from the ray and the hit's t and part.
  { p.fillHit(v, v, x, part, hit) } -> std::same_as<void>;
  /// Its curvature at a hit: d n / d x applied to a motion dx of the point along the surface
  /// (the shape operator; zero where it is flat), for shape derivatives.
  { p.normalTurning(std::as_const(hit), Vec3()) } -> std::same_as<Vec3>;
  /// Its surface area.
  { p.area() } -> std::same_as<double>;
  /// A point uniformly by area (density 1 / area()).
  { p.sampleArea(u) } -> std::same_as<AreaSample>;
  /// The one direction all of its normals share (a flat primitive's front), if any: the
  /// normal cone of its light bounds.
  { p.facing() } -> std::same_as<std::optional<Vec3d>>;
  /// Whether its light can fall on itself (next-event estimation skips what cannot).
  { P::kSelfLighting } -> std::convertible_to<SelfLighting>;
  /// Whether the boundary terms of shape derivatives sample its outline (silhouette and edges)
  /// as seen from a point; where they do not, derivatives refuse a moving camera and warn.
  { P::kOutlineSampled } -> std::convertible_to<bool>;
  /// Flux per unit radiance when it emits uniformly: pi times the area whose light leaves it
  /// (both faces of open and flat primitives, the outside of closed ones).
  { p.fluxPerRadiance() } -> std::same_as<double>;
  /// Irradiance per unit radiance on its axis at distance d from its centre, for emitters
  /// measured there (at="..."); throws nx::Error naming `where` if it has no such axis.
  { p.axialIrradiancePerRadiance(x, where) } -> std::same_as<double>;
};

} // namespace nx
