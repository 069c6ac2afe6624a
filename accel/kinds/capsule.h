#pragma once
// A capsule, <capsule><p0/><p1/><radius/>: the points within `radius` of the segment p0 -> p1
// (a test tube or a rounded cuvette: a cylinder closed by two hemispheres). Embree user
// geometry intersected exactly in double precision; it can hold a <medium>, and as a light its
// outside emits, sampled uniformly by area (MIS with the BSDF).

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "accel/primitive.h"
#include "accel/shape_schema.h"
#include "core/error.h"
#include "core/math_util.h"
#include "core/ray_offset.h"
#include "core/vec3.h"

namespace nx {

/// Which part of a capsule a point is on: the tube, the hemisphere around p0 or around p1.
enum class CapsulePart : uint8_t { Side, Base, Top };

/// Both roots t0 <= t1 of |o + t d - c|^2 = r^2, if real: the closest-approach discriminant
/// and the stable pair of roots (Haines et al., Ray Tracing Gems ch. 7), as intersectSphere.
inline std::optional<std::pair<double, double>> sphereRoots(const Vec3d& c, double r,
                                                            const Vec3d& o, const Vec3d& d) {
  const Vec3d f = o - c;
  const double a = dot(d, d), b = -dot(f, d);
  const Vec3d l = f + d * (b / a);
  const double disc = a * (r * r - dot(l, l));
  if (!(disc >= 0)) return std::nullopt;
  const double q = b + std::copysign(std::sqrt(disc), b);
  double t0 = q == 0 ? 0 : (dot(f, f) - r * r) / q, t1 = q == 0 ? 0 : q / a;
  if (t0 > t1) std::swap(t0, t1);
  return std::pair(t0, t1);
}

/// A capsule: the points within `radius` of the segment p0 -> p1 (p0 != p1). Its surface: the
/// tube of the segment's length and two hemispheres. uv: u = phi / 2 pi around the axis (from
/// AxisFrame::s), v = arc length from the pole beyond p0 along a meridian, over the meridian's
/// length |p1 - p0| + pi r (so the parts meet without a seam in v).
struct CapsuleShape {
  Vec3d p0, p1{0, 1, 0};
  double radius = 1;
  bool operator==(const CapsuleShape&) const = default;
  /// Unit axis from p0 to p1.
  Vec3d axis() const { return normalize(p1 - p0); }
  /// The tube's length.
  double height() const { return length(p1 - p0); }

  /// Its box: the two end spheres' boxes.
  BoundingBox bounds() const {
    const Vec3d r(radius, radius, radius);
    return {Vec3d(std::min(p0.x, p1.x), std::min(p0.y, p1.y), std::min(p0.z, p1.z)) - r,
            Vec3d(std::max(p0.x, p1.x), std::max(p0.y, p1.y), std::max(p0.z, p1.z)) + r};
  }

  /// The nearest hit in (tMin, tMax): the tube's quadratic (its points between the ends), then
  /// each end sphere's two roots (their points beyond their end). d need not be unit length.
  std::optional<PrimitiveHit> intersect(const Vec3d& o, const Vec3d& d, double tMin,
                                        double tMax) const {
    const Vec3d a = axis();
    const double h = height();
    const Vec3d w = o - p0;
    std::optional<PrimitiveHit> best;
    auto consider = [&](double t, CapsulePart part) {
      if (t > tMin && t < (best ? best->t : tMax)) best = PrimitiveHit{t, uint32_t(part)};
    };
    const Vec3d wp = w - a * dot(w, a), dp = d - a * dot(d, a); // across the axis
    const double qa = dot(dp, dp);
    if (qa > 0) {
      const double b = -dot(wp, dp);
      const Vec3d l = wp + dp * (b / qa); // closest approach to the axis
      const double disc = qa * (radius * radius - dot(l, l));
      if (disc >= 0) {
        const double c = dot(wp, wp) - radius * radius;
        const double q = b + std::copysign(std::sqrt(disc), b);
        for (const double t : {q == 0 ? 0 : c / q, q == 0 ? 0 : q / qa}) {
          const double z = dot(w + d * t, a);
          if (z >= 0 && z <= h) consider(t, CapsulePart::Side);
        }
      }
    }
    for (const CapsulePart part : {CapsulePart::Base, CapsulePart::Top}) {
      const Vec3d c = part == CapsulePart::Base ? p0 : p1;
      if (const auto roots = sphereRoots(c, radius, o, d))
        for (const double t : {roots->first, roots->second}) {
          const double z = dot(o + d * t - c, a); // beyond its end: away from the other
          if (part == CapsulePart::Base ? z < 0 : z > 0) consider(t, part);
        }
    }
    return best;
  }

  /// The point projected onto its part in double (the tube: radius from the axis; an end: from
  /// its centre), the outward normal, uv and dp/du.
  void fillHit(const Vec3d& o, const Vec3d& d, double t, uint32_t part, SurfaceHit& hit) const {
    const Vec3d a = axis();
    const AxisFrame f = AxisFrame::of(a);
    const double h = height();
    const Vec3d q = o + d * t - p0;
    const double z = dot(q, a);
    const Vec3d across = q - a * z;
    hit.u = turnFraction(dot(across, f.t), dot(across, f.s));
    const double meridian = h + kPi * radius;
    Vec3d n, p;
    double arc; // from the pole beyond p0
    if (static_cast<CapsulePart>(part) == CapsulePart::Side) {
      const double r = length(across);
      n = r > 0 ? across * (1 / r) : f.s;
      const double zc = std::clamp(z, 0.0, h);
      p = p0 + a * zc + n * radius;
      arc = kPi / 2 * radius + zc;
    } else {
      const bool base = static_cast<CapsulePart>(part) == CapsulePart::Base;
      const Vec3d c = base ? p0 : p1;
      n = normalize(q + p0 - c);
      p = c + n * radius;
      // the angle from the pole beyond this end: acos(-n.a) at the base, acos(n.a) at the top
      const double polar = std::acos(std::clamp(base ? -dot(n, a) : dot(n, a), -1.0, 1.0));
      arc = base ? radius * polar : meridian - radius * polar;
    }
    hit.p = Vec3(p);
    hit.ng = hit.ns = Vec3(n);
    hit.v = static_cast<float>(std::clamp(arc / meridian, 0.0, 1.0));
    const Vec3d fromAxis = p - p0 - a * dot(p - p0, a);
    const Vec3d dpdu = cross(a, fromAxis) * (2 * kPi);
    hit.dpdu = length(dpdu) > 0 ? Vec3(dpdu) : Vec3(f.s); // (at a pole: any tangent)
    hit.pError = roundingError(hit.p);
  }

  /// The ends turn the normal as a sphere's, (I - n n^T) dx / r; the tube as a cylinder's,
  /// by the motion across the axis over the radius.
  Vec3 normalTurning(const SurfaceHit& hit, const Vec3& dx) const {
    Vec3 moved = dx;
    if (hit.prim == static_cast<uint32_t>(CapsulePart::Side)) {
      const Vec3 a(axis());
      moved = dx - a * dot(a, dx);
    }
    return (moved - hit.ng * dot(hit.ng, moved)) * static_cast<float>(1 / radius);
  }

  /// Its area: the tube's 2 pi r h and a whole sphere's 4 pi r^2.
  double area() const { return 2 * kPi * radius * height() + 4 * kPi * radius * radius; }

  /// A point uniformly by area: a part in proportion to its area (u.u reused within the
  /// part's share), the tube by height and angle, an end by the hemisphere's cos(theta),
  /// uniform in [0, 1] (Archimedes), and angle (density 1 / area).
  AreaSample sampleArea(Sample2 u) const {
    const Vec3d a = axis();
    const AxisFrame f = AxisFrame::of(a);
    const double phi = 2 * kPi * double(u.v);
    const Vec3d around = f.s * std::cos(phi) + f.t * std::sin(phi);
    const double h = height(), side = 2 * kPi * radius * h / area();
    if (double(u.u) < side) {
      const double z = std::min(double(u.u) / side, 1.0) * h;
      return {p0 + a * z + around * radius, around, uint32_t(CapsulePart::Side)};
    }
    const double w = (double(u.u) - side) / (1 - side); // in [0, 1): half each end
    const bool base = w < 0.5;
    const double cosTheta = std::min(base ? 2 * w : 2 * w - 1, 1.0); // from the pole
    const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
    const Vec3d n = a * (base ? -cosTheta : cosTheta) + around * sinTheta;
    return {(base ? p0 : p1) + n * radius, n,
            uint32_t(base ? CapsulePart::Base : CapsulePart::Top)};
  }

  /// Its volume: the tube's pi r^2 h and a whole sphere's 4/3 pi r^3 (it can hold a medium).
  double volume() const {
    return kPi * radius * radius * height() + 4.0 / 3.0 * kPi * radius * radius * radius;
  }
  /// True for points strictly inside: nearer the segment than the radius.
  bool contains(const Vec3d& x) const {
    const Vec3d a = axis();
    const double z = std::clamp(dot(x - p0, a), 0.0, height());
    return length(x - (p0 + a * z)) < radius;
  }

  /// Curved: no one facing direction.
  std::optional<Vec3d> facing() const { return std::nullopt; }
  /// Its silhouette seen from o: the tube's two lines (o off the tube) and each end
  /// sphere's silhouette where it lies beyond its end.
  void outlines(const Vec3d& o, OutlineCurves& out) const {
    const Vec3d a = axis();
    tubeSilhouette(p0, p1, a, radius, o, uint32_t(CapsulePart::Side), out);
    for (const CapsulePart part : {CapsulePart::Base, CapsulePart::Top}) {
      const bool base = part == CapsulePart::Base;
      OutlineCurve c;
      if (!sphereSilhouette(base ? p0 : p1, radius, o, c, uint32_t(part))) continue;
      c.keepFrom = base ? p0 : p1;
      c.keepAxis = base ? a * -1.0 : a;
      out.add(c);
    }
  }
  /// The point at the same angle (turned with the axis by the shortest rotation) and fraction
  /// of the length on `moved`'s tube, or in the same turned direction from its end's centre.
  CarriedPoint carry(const CapsuleShape& moved, const Vec3d& x, uint32_t part) const {
    const Vec3d a = axis(), ma = moved.axis();
    if (static_cast<CapsulePart>(part) == CapsulePart::Side) {
      const Vec3d q = x - p0;
      const double z = dot(q, a);
      const Vec3d n = normalize(rotateBetween(a, ma, q - a * z));
      return {moved.p0 + ma * (z / height() * moved.height()) + n * moved.radius, n};
    }
    const bool base = static_cast<CapsulePart>(part) == CapsulePart::Base;
    const Vec3d n = rotateBetween(a, ma, normalize(x - (base ? p0 : p1)));
    return {(base ? moved.p0 : moved.p1) + n * moved.radius, n};
  }
  /// Closed and convex: its light reaches itself only inside.
  static constexpr SelfLighting kSelfLighting = SelfLighting::FromInside;
  /// Closed: only the outside's light leaves, pi times its area.
  double fluxPerRadiance() const { return kPi * area(); }
  /// Not flat: no axis to measure on.
  double axialIrradiancePerRadiance(double, const std::string& where) const {
    throw Error(where + ": expected a flat emitter for at=\"...\" (a triangle, a quad, a disk "
                        "or a planar mesh), found a capsule (give its total flux with "
                        "quantity=\"flux\")");
  }
};

/// The capsule kind.
struct CapsuleShapeKind {
  static constexpr const char* kName = "capsule";
  static constexpr const char* kDoc =
      "the points within `radius` of the segment p0 -> p1: a tube closed by two hemispheres, "
      "e.g. a test tube (exact double-precision intersection); it can hold a <medium>; as a "
      "light its outside emits, sampled by area";
  static constexpr bool kHoldsMedium = true;
  /// Its parameters.
  static std::span<const ShapeParameter> parameters() {
    static const ShapeParameter p[] = {
        {differentiable({"p0", ParamType::Point, "scene units", nullptr,
                         "the centre of one end's hemisphere", "0, 0.3, 0", "",
                         "an end's centre x, y, z"})},
        {differentiable({"p1", ParamType::Point, "scene units", nullptr,
                         "the centre of the other end's hemisphere", "0, 1.2, 0", "",
                         "an end's centre x, y, z"})},
        {differentiable(
            {"radius", ParamType::Number, "scene units", &kRadiusRange, "its radius", "0.3"})},
    };
    return p;
  }
  /// Equal ends make a sphere, not a capsule.
  static std::optional<ShapeProblem> problem(const ParameterSet& p) {
    if (length(*p.get<Vec3d>("p1") - *p.get<Vec3d>("p0")) > 0) return std::nullopt;
    return ShapeProblem{"a capsule whose ends p0 and p1 differ (a <sphere> for equal ones)",
                        "equal ends"};
  }
  /// Its primitive, from checked parameters.
  static CapsuleShape build(const ParameterSet& p, const ShapeInputs&) {
    return {*p.get<Vec3d>("p0"), *p.get<Vec3d>("p1"), *p.number("radius")};
  }
};

} // namespace nx
