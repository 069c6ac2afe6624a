#pragma once
// What an analytic primitive (a sphere, a disk, a cylinder, a capsule: Embree user geometry)
// owns, so that the geometry, the light sampler, the measured emitter and the gradient code
// ask it instead of branching on its kind. A primitive is a struct in its kind's header
// (accel/kinds/) that satisfies AnalyticPrimitive; the list NX_ANALYTIC_PRIMITIVES
// (accel/shape_kind.h) registers it, and everything else is generated from that list.

#include <array>
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

/// The shortest rotation taking unit vector a to unit vector b, applied to v (Rodrigues'
/// formula with k = a x b: v (a . b) + k x v + k (k . v) / (1 + a . b); a != -b).
inline Vec3d rotateBetween(const Vec3d& a, const Vec3d& b, const Vec3d& v) {
  const Vec3d k = cross(a, b);
  const double c = dot(a, b);
  return v * c + cross(k, v) + k * (dot(k, v) / (1 + c));
}

/// A material point of a primitive as a moved copy of the primitive has it: its position and
/// unit normal. The gradient code differences these in double to get how a parameter moves
/// the surface (docs/inverse.md, "Shape and camera").
struct CarriedPoint {
  Vec3d p, n;
};

/// A curve on a primitive across which what a point sees of it can jump: a silhouette (where
/// the lines from the point touch the surface) or an edge (a rim). A circle (centre c, radius,
/// in the plane of the unit vectors u and v) or a segment a -> b, over s in [0, 1). Where
/// keepAxis is not zero only its points x with (x - keepFrom) . keepAxis >= 0 belong to it (a
/// capsule's end silhouettes, cut to their hemisphere). The boundary terms of shape
/// derivatives sample it (docs/inverse.md, "Shape and camera").
struct OutlineCurve {
  bool segment = false;
  Vec3d c, u, v;     ///< a circle's centre and plane
  double radius = 0; ///< a circle's radius
  Vec3d a, b;        ///< a segment's ends
  Vec3d keepFrom, keepAxis;
  uint32_t part = 0; ///< the part of the primitive its points are on
  double size = 0;   ///< the primitive's scale (a ray grazing it is looked at from 1% of it on)
  /// Its point at s.
  Vec3d at(double s) const {
    if (segment) return a + (b - a) * s;
    const double t = 2 * kPi * s;
    return c + (u * std::cos(t) + v * std::sin(t)) * radius;
  }
  /// d at / d s.
  Vec3d tangent(double s) const {
    if (segment) return b - a;
    const double t = 2 * kPi * s;
    return (u * -std::sin(t) + v * std::cos(t)) * (2 * kPi * radius);
  }
  /// True when x (a point of the curve) belongs to the outline.
  bool keeps(const Vec3d& x) const { return dot(x - keepFrom, keepAxis) >= 0; }
  /// The circle around c of `radius` perpendicular to unit `axis`.
  static OutlineCurve circle(const Vec3d& c, const Vec3d& axis, double radius, uint32_t part,
                             double size) {
    const AxisFrame f = AxisFrame::of(axis);
    OutlineCurve o;
    o.c = c, o.u = f.s, o.v = f.t, o.radius = radius, o.part = part, o.size = size;
    return o;
  }
  /// The segment a -> b.
  static OutlineCurve line(const Vec3d& a, const Vec3d& b, uint32_t part, double size) {
    OutlineCurve o;
    o.segment = true, o.a = a, o.b = b, o.part = part, o.size = size;
    return o;
  }
};

/// The outline curves of a primitive seen from a point (at most four: a cylinder's two
/// silhouette lines and two rims).
struct OutlineCurves {
  std::array<OutlineCurve, 4> curve;
  int count = 0;
  /// Appends c.
  void add(const OutlineCurve& c) { curve[static_cast<size_t>(count++)] = c; }
};

/// The silhouette of the sphere (c, r) seen from o: the circle where the lines from o touch
/// it; false when o is inside it or on it.
inline bool sphereSilhouette(const Vec3d& c, double r, const Vec3d& o, OutlineCurve& out,
                             uint32_t part = 0) {
  const Vec3d a = c - o;
  const double d2 = dot(a, a), r2 = r * r;
  if (!(d2 > r2 * (1 + 1e-9))) return false;
  const double k = 1 - r2 / d2;
  out = OutlineCurve::circle(o + a * k, normalize(a), r * std::sqrt(k), part, r);
  return true;
}

/// The two lines where the lines from o touch the tube of radius r around the segment
/// p0 -> p1 (unit axis a), added to `out`; none when o is within r of the axis.
inline void tubeSilhouette(const Vec3d& p0, const Vec3d& p1, const Vec3d& a, double r,
                           const Vec3d& o, uint32_t part, OutlineCurves& out) {
  const Vec3d w = o - p0, across = w - a * dot(w, a);
  const double d = length(across);
  if (!(d > r * (1 + 1e-9))) return;
  const Vec3d e = across / d, f = cross(a, e);
  const double cosB = r / d, sinB = std::sqrt(std::max(0.0, 1 - cosB * cosB));
  for (const double side : {1.0, -1.0}) {
    const Vec3d radial = (e * cosB + f * (side * sinB)) * r;
    out.add(OutlineCurve::line(p0 + radial, p1 + radial, part, r));
  }
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
                                     SurfaceHit& hit, Sample2 u, const std::string& where,
                                     OutlineCurves& curves) {
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
  /// Its outline seen from a point (silhouettes and rims) into `curves`, for the boundary
  /// terms of shape derivatives.
  { p.outlines(v, curves) } -> std::same_as<void>;
  /// Where the material point at a point of its `part` is on a moved copy of it (`p` itself
  /// here), and its normal there: how its parameters move its surface, for shape derivatives.
  { p.carry(p, v, part) } -> std::same_as<CarriedPoint>;
  /// Flux per unit radiance when it emits uniformly: pi times the area whose light leaves it
  /// (both faces of open and flat primitives, the outside of closed ones).
  { p.fluxPerRadiance() } -> std::same_as<double>;
  /// Irradiance per unit radiance on its axis at distance d from its centre, for emitters
  /// measured there (at="..."); throws nx::Error naming `where` if it has no such axis.
  { p.axialIrradiancePerRadiance(x, where) } -> std::same_as<double>;
};

} // namespace nx
