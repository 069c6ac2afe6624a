#pragma once
// A sphere, <sphere><center>x, y, z</center><radius>r</radius>: Embree user geometry,
// intersected exactly in double precision; it can hold a <medium>, and as an emitter the light
// sampler samples the cone it subtends.

#include <algorithm>
#include <cmath>
#include <optional>

#include "accel/primitive.h"
#include "accel/shape_schema.h"
#include "core/direction_sampling.h"
#include "core/error.h"
#include "core/frame.h"
#include "core/math_util.h"
#include "core/ray_offset.h"
#include "core/vec3.h"

namespace nx {

struct SphereShape;
/// Nearest ray parameter where a ray meets the sphere (defined below).
inline std::optional<double> intersectSphere(const SphereShape& s, const Vec3d& o, const Vec3d& d,
                                             double tMin, double tMax);

/// A sphere. uv: u = phi / 2 pi around +y from +z towards +x, v = theta / pi from +y, filled
/// in only where a texture asks (lazyUv).
struct SphereShape {
  Vec3d center;
  double radius = 1;
  /// Every field compared (the geometry cache reuses a BVH only for equal shapes).
  bool operator==(const SphereShape&) const = default;
  /// Its box.
  BoundingBox bounds() const {
    const Vec3d r(radius, radius, radius);
    return {center - r, center + r};
  }
  /// Its nearest hit (intersectSphere).
  std::optional<PrimitiveHit> intersect(const Vec3d& o, const Vec3d& d, double tMin,
                                        double tMax) const {
    const auto t = intersectSphere(*this, o, d, tMin, tMax);
    return t ? std::optional(PrimitiveHit{*t, 0}) : std::nullopt;
  }
  /// The point re-projected onto the surface in double precision (then as accurate as the
  /// float it is stored in, whatever the sphere's size), the outward normal, dp/du; uv later.
  void fillHit(const Vec3d& o, const Vec3d& d, double t, uint32_t, SurfaceHit& hit) const {
    const Vec3d n = normalize(o + d * t - center);
    hit.p = Vec3(center + n * radius);
    hit.ng = Vec3(n);
    hit.ns = hit.ng;
    hit.u = hit.v = 0;
    hit.uvPending = true; // lazyUv computes them when a texture needs them
    hit.dpdu = Vec3(Vec3d(n.z, 0, -n.x) * (2 * kPi * radius));
    hit.pError = roundingError(hit.p);
  }
  /// Fills a hit's (u, v) from its normal (left out of fillHit so that untextured spheres do
  /// not pay for the arc functions).
  static void lazyUv(SurfaceHit& hit) {
    const Vec3d n(hit.ng);
    hit.u = turnFraction(n.x, n.z);
    hit.v = static_cast<float>(std::acos(std::clamp(n.y, -1.0, 1.0)) / kPi);
  }
  /// (I - n n^T) dx / r: a sphere turns its normal by the motion across it over its radius.
  Vec3 normalTurning(const SurfaceHit& hit, const Vec3& dx) const {
    return (dx - hit.ng * dot(hit.ng, dx)) * static_cast<float>(1 / radius);
  }
  /// Its area 4 pi r^2.
  double area() const { return 4 * kPi * radius * radius; }
  /// A point uniformly by area: z = 1 - 2 u, phi = 2 pi v (Archimedes' hat-box theorem).
  AreaSample sampleArea(Sample2 u) const {
    const double z = 1 - 2 * double(u.u), r = std::sqrt(std::max(0.0, 1 - z * z));
    const double phi = 2 * kPi * double(u.v);
    const Vec3d n(r * std::cos(phi), r * std::sin(phi), z);
    return {center + n * radius, n, 0};
  }
  /// Its volume 4/3 pi r^3 (it bounds one: it can hold a medium).
  double volume() const { return 4.18879020478639 * radius * radius * radius; }
  /// True for points strictly inside.
  bool contains(const Vec3d& p) const {
    const Vec3d d = p - center;
    return std::sqrt(dot(d, d)) < radius;
  }
  /// A direction uniformly within the cone the sphere subtends from p (every direction from
  /// inside), the distance to the near side along it and the point there, projected onto the
  /// surface in double precision; nothing where the configuration is degenerate.
  std::optional<SolidAngleSample> sampleSolidAngle(const Vec3& p, Sample2 u) const {
    const Vec3d axis = center - Vec3d(p);
    const double d2 = dot(axis, axis);
    const double r2 = radius * radius;
    SolidAngleSample s;
    if (d2 <= r2) {
      s.wi = sampleUniformSphere(u); // inside: every direction meets the sphere
      s.pdf = 1.0 / (4 * kPi);
      const auto t = intersectSphere(*this, Vec3d(p), Vec3d(s.wi), 0.0, INFINITY);
      s.distance = t ? *t : 0.0;
    } else {
      // Few dependent divisions and square roots: they are most of this function's time.
      const double d = std::sqrt(d2), invD = 1.0 / d;
      const double oneMinusCosMax = oneMinusCosFromSin2(r2 * invD * invD);
      // The frame and the local direction are unit to float rounding, so wi is too.
      s.wi = Frame::fromNormal(Vec3(axis * invD)).toWorld(sampleUniformCone(u, oneMinusCosMax));
      s.pdf = uniformConePdf(oneMinusCosMax);
      // Distance to the near side along the sampled theta (law of cosines), in double: the
      // same 1 - cos(theta) as sampleUniformCone. Directions at the silhouette get the tangent
      // distance (the square root is zero up to rounding).
      const double oneMinusCos = u.u * oneMinusCosMax;
      const double sin2 = oneMinusCos * (2.0 - oneMinusCos);
      s.distance = d * (1.0 - oneMinusCos) - std::sqrt(std::max(0.0, r2 - d2 * sin2));
    }
    if (!(s.distance > 0) || !std::isfinite(s.pdf)) return std::nullopt;
    s.n = normalize(Vec3d(p) + Vec3d(s.wi) * s.distance - center);
    s.p = center + s.n * radius;
    return s;
  }
  /// Density of sampleSolidAngle for direction wi from p (0 outside the cone).
  double solidAnglePdf(const Vec3& p, const Vec3& wi) const {
    const Vec3d axis = center - Vec3d(p);
    const double d2 = dot(axis, axis), r2 = radius * radius;
    if (d2 <= r2) return 1.0 / (4 * kPi);
    const double oneMinusCosMax = oneMinusCosFromSin2(r2 / d2);
    if (dot(axis, Vec3d(wi)) / std::sqrt(d2) < 1.0 - oneMinusCosMax) return 0; // outside
    return uniformConePdf(oneMinusCosMax);
  }
  /// Itself.
  std::pair<Vec3d, double> boundingSphere() const { return {center, radius}; }
  /// Curved: no one facing direction.
  std::optional<Vec3d> facing() const { return std::nullopt; }
  /// Its silhouette seen from o, where o is outside it.
  void outlines(const Vec3d& o, OutlineCurves& out) const {
    OutlineCurve c;
    if (sphereSilhouette(center, radius, o, c)) out.add(c);
  }
  /// The point of the same direction from the centre on `moved`.
  CarriedPoint carry(const SphereShape& moved, const Vec3d& x, uint32_t) const {
    const Vec3d n = normalize(x - center);
    return {moved.center + n * moved.radius, n};
  }
  /// Closed and convex: its light reaches itself only inside.
  static constexpr SelfLighting kSelfLighting = SelfLighting::FromInside;
  /// Its outward flux per radiance, pi times its area (4 pi^2 r^2).
  double fluxPerRadiance() const { return 4 * kPi * kPi * radius * radius; }
  /// pi r^2 / d^2 at distance d > r from its centre, in any direction.
  double axialIrradiancePerRadiance(double d, const std::string& where) const {
    if (!(d > radius))
      throw Error(where + ": expected a measuring distance beyond the sphere's radius " +
                  numberText(radius) + " (from its centre), found " + numberText(d));
    return kPi * radius * radius / (d * d);
  }
};

/// Nearest ray parameter t in (tMin, tMax) where o + t d meets the sphere, if any. Uses the
/// closest-approach form of the discriminant and the stable pair of roots (Haines et al.,
/// "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems, ch. 7), so it is
/// accurate for tiny and huge spheres; both roots are considered, so a ray starting inside
/// finds the far side. d need not be unit length.
inline std::optional<double> intersectSphere(const SphereShape& s, const Vec3d& o, const Vec3d& d,
                                             double tMin, double tMax) {
  const Vec3d f = o - s.center;
  const double a = dot(d, d);
  const double b = -dot(f, d);     // half of the usual b, negated
  const Vec3d l = f + d * (b / a); // closest approach of the line to the centre
  const double disc = a * (s.radius * s.radius - dot(l, l)); // = b^2 - a c
  if (!(disc >= 0)) return std::nullopt;
  const double c = dot(f, f) - s.radius * s.radius;
  const double q = b + std::copysign(std::sqrt(disc), b);
  double t0, t1;
  if (q == 0) {
    t0 = t1 = 0; // o on the surface, tangent: the only root is 0
  } else {
    t0 = c / q;
    t1 = q / a;
  }
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > tMin && t0 < tMax) return t0;
  if (t1 > tMin && t1 < tMax) return t1;
  return std::nullopt;
}

/// The sphere kind.
struct SphereShapeKind {
  static constexpr const char* kName = "sphere";
  static constexpr const char* kDoc =
      "a sphere (exact double-precision intersection); it can hold a <medium>";
  static constexpr bool kHoldsMedium = true;
  /// Its parameters.
  static std::span<const ShapeParameter> parameters() {
    static const ShapeParameter p[] = {
        {differentiable({"center", ParamType::Point, "scene units", nullptr, "its centre",
                         "0, 1, 0", "", "a sphere centre x, y, z"})},
        {differentiable(
            {"radius", ParamType::Number, "scene units", &kRadiusRange, "its radius", "1"})},
    };
    return p;
  }
  /// Nothing beyond each value's type and range.
  static std::optional<ShapeProblem> problem(const ParameterSet&) { return std::nullopt; }
  /// Its primitive, from checked parameters.
  static SphereShape build(const ParameterSet& p, const ShapeInputs&) {
    return {*p.get<Vec3d>("center"), *p.number("radius")};
  }
};

} // namespace nx
