#pragma once
// A cylinder, <cylinder><p0/><p1/><radius/><capped/>: the tube of `radius` around the segment
// p0 -> p1, open or closed by two disks; Embree user geometry intersected exactly in double
// precision (the closest-approach quadratic, as for spheres, then the caps); as a light every
// part emits on both sides, sampled uniformly by area (MIS with the BSDF).

#include <cmath>
#include <optional>

#include <algorithm>
#include <string>

#include "accel/kinds/disk.h"
#include "core/error.h"

namespace nx {

/// Which part of a cylinder a hit is on.
enum class CylinderPart : uint8_t { Side, Base, Top };

struct CylinderShape;
/// A hit on a cylinder: the ray parameter and the part.
struct CylinderHit {
  double t;
  CylinderPart part;
};
/// The nearest hit of a ray with the cylinder (defined below).
inline std::optional<CylinderHit> intersectCylinder(const CylinderShape& s, const Vec3d& o,
                                                    const Vec3d& d, double tMin, double tMax);

/// A cylinder of `radius` around the segment p0 -> p1, with two caps (disks at p0 facing
/// away from p1, at p1 facing away from p0) when `capped`. uv: the side's u = phi / 2 pi around
/// the axis (from AxisFrame::s), v = height / length; a cap's polar coordinates as a disk's.
struct CylinderShape {
  Vec3d p0, p1{0, 1, 0};
  double radius = 1;
  bool capped = false;
  bool operator==(const CylinderShape&) const = default;
  /// Unit axis from p0 to p1.
  Vec3d axis() const { return normalize(p1 - p0); }
  /// Its length along the axis.
  double height() const { return length(p1 - p0); }
  /// Area of the side.
  double sideArea() const { return 2 * kPi * radius * height(); }
  /// Area of all its parts.
  double area() const { return sideArea() + (capped ? 2 * kPi * radius * radius : 0); }
  /// Its box: the two end circles' boxes.
  BoundingBox bounds() const {
    const Vec3d e = circleExtent(axis(), radius);
    return {Vec3d(std::min(p0.x, p1.x), std::min(p0.y, p1.y), std::min(p0.z, p1.z)) - e,
            Vec3d(std::max(p0.x, p1.x), std::max(p0.y, p1.y), std::max(p0.z, p1.z)) + e};
  }
  /// Its nearest hit and part (intersectCylinder).
  std::optional<PrimitiveHit> intersect(const Vec3d& o, const Vec3d& d, double tMin,
                                        double tMax) const {
    const auto h = intersectCylinder(*this, o, d, tMin, tMax);
    return h ? std::optional(PrimitiveHit{h->t, static_cast<uint32_t>(h->part)}) : std::nullopt;
  }
  /// The side: the point re-projected onto the tube (radius from the axis, in double), the
  /// outward normal, cylindrical uv; a cap: as a disk.
  void fillHit(const Vec3d& o, const Vec3d& d, double t, uint32_t part, SurfaceHit& hit) const {
    const Vec3d a = axis();
    const AxisFrame f = AxisFrame::of(a);
    const Vec3d q = o + d * t - p0;
    const double z = dot(q, a);
    const Vec3d across = q - a * z;
    const double x = dot(across, f.s), y = dot(across, f.t);
    hit.u = turnFraction(y, x);
    if (static_cast<CylinderPart>(part) == CylinderPart::Side) {
      const double r = length(across);
      const Vec3d radial = r > 0 ? across * (1 / r) : f.s;
      hit.p = Vec3(p0 + a * z + radial * radius);
      hit.ng = hit.ns = Vec3(radial);
      hit.v = static_cast<float>(std::clamp(z / height(), 0.0, 1.0));
      hit.dpdu = Vec3(cross(a, radial) * (2 * kPi * radius));
    } else {
      const DiskShape c = cap(static_cast<CylinderPart>(part));
      const Vec3d onCap =
          q - a * (z - (static_cast<CylinderPart>(part) == CylinderPart::Top ? height() : 0.0));
      hit.p = Vec3(p0 + onCap);
      hit.ng = hit.ns = Vec3(c.normal);
      hit.v = static_cast<float>(std::min(1.0, length(across) / radius));
      const Vec3d dpdu = (f.t * x - f.s * y) * (2 * kPi);
      hit.dpdu = length(dpdu) > 0 ? Vec3(dpdu) : Vec3(f.s);
    }
    hit.pError = roundingError(hit.p);
  }
  /// The side turns its normal by the motion across the axis over the radius (as a sphere's,
  /// without the axial part); the flat caps turn nothing.
  Vec3 normalTurning(const SurfaceHit& hit, const Vec3& dx) const {
    if (hit.prim != static_cast<uint32_t>(CylinderPart::Side)) return {};
    const Vec3 a(axis());
    const Vec3 across = dx - a * dot(a, dx);
    return (across - hit.ng * dot(hit.ng, across)) * static_cast<float>(1 / radius);
  }
  /// The cap at p0 (part Base) or p1 (Top).
  DiskShape cap(CylinderPart part) const {
    const Vec3d a = axis();
    return part == CylinderPart::Base ? DiskShape{p0, a * -1.0, radius} : DiskShape{p1, a, radius};
  }
  /// A point uniformly by area: a part in proportion to its area (u.u reused within the part's
  /// share), the side by height and angle, a cap as a disk (density 1 / area).
  AreaSample sampleArea(Sample2 u) const {
    const double side = sideArea() / area();
    if (u.u < side || !capped) {
      const double v = capped ? u.u / side : u.u;
      const Vec3d a = axis();
      const AxisFrame f = AxisFrame::of(a);
      const double phi = 2 * kPi * u.v;
      const Vec3d normal = f.s * std::cos(phi) + f.t * std::sin(phi);
      return {p0 + a * (std::min(v, 1.0) * height()) + normal * radius, normal,
              static_cast<uint32_t>(CylinderPart::Side)};
    }
    const double v = (u.u - side) / (1 - side); // in [0, 1): half each cap
    const CylinderPart part = v < 0.5 ? CylinderPart::Base : CylinderPart::Top;
    const float w = static_cast<float>(v < 0.5 ? 2 * v : 2 * v - 1);
    AreaSample s = cap(part).sampleArea(Sample2{std::min(w, 0x1.fffffep-1f), u.v});
    s.part = static_cast<uint32_t>(part);
    return s;
  }
  /// Curved: no one facing direction.
  std::optional<Vec3d> facing() const { return std::nullopt; }
  /// Seen from o: the side's two silhouette lines (o off the tube) and the two rims (the
  /// edges of an open tube, or where the caps meet the side).
  void outlines(const Vec3d& o, OutlineCurves& out) const {
    const Vec3d a = axis();
    const uint32_t side = static_cast<uint32_t>(CylinderPart::Side);
    tubeSilhouette(p0, p1, a, radius, o, side, out);
    out.add(OutlineCurve::circle(p0, a, radius, side, radius));
    out.add(OutlineCurve::circle(p1, a, radius, side, radius));
  }
  /// The point at the same angle (turned with the axis by the shortest rotation) and fraction
  /// of the length on `moved`'s side, or at the same polar coordinates on its cap.
  CarriedPoint carry(const CylinderShape& moved, const Vec3d& x, uint32_t part) const {
    const Vec3d a = axis(), ma = moved.axis();
    const Vec3d q = x - p0;
    const double z = dot(q, a);
    const Vec3d across = q - a * z, turned = rotateBetween(a, ma, across);
    if (static_cast<CylinderPart>(part) == CylinderPart::Side) {
      const Vec3d n = normalize(turned);
      return {moved.p0 + ma * (z / height() * moved.height()) + n * moved.radius, n};
    }
    const bool base = static_cast<CylinderPart>(part) == CylinderPart::Base;
    return {(base ? moved.p0 : moved.p1) + turned * (moved.radius / radius), base ? ma * -1.0 : ma};
  }
  /// Open or not: its inside can light itself (shadow rays tell).
  static constexpr SelfLighting kSelfLighting = SelfLighting::Possible;
  /// The flux that leaves it per unit radiance: a capped one's outside, pi times its area (its
  /// inward light never leaves); an open tube's outside, pi A_side, and what leaves its inside
  /// through its two open ends: by reciprocity, pi (pi r^2) (1 - F) through each, F the view
  /// factor between the two end disks (coaxial, radius r, h apart: F = (S - sqrt(S^2 - 4)) / 2,
  /// S = 2 + h^2 / r^2; Siegel & Howell, Thermal Radiation Heat Transfer, table of view factors).
  double fluxPerRadiance() const {
    if (capped) return kPi * area();
    const double s = 2 + height() * height() / (radius * radius);
    const double endToEnd = (s - std::sqrt(s * s - 4)) / 2;
    return kPi * sideArea() + 2 * kPi * kPi * radius * radius * (1 - endToEnd);
  }
  /// Not flat: no axis to measure on.
  double axialIrradiancePerRadiance(double, const std::string& where) const {
    throw Error(where + ": expected a flat emitter for at=\"...\" (a triangle, a quad, a disk "
                        "or a planar mesh), found a cylinder (give its total flux with "
                        "quantity=\"flux\")");
  }
};

/// The nearest hit of o + t d with t in (tMin, tMax), if any. The side: the quadratic of the
/// ray projected across the axis, its discriminant from the closest approach (Haines et al.,
/// Ray Tracing Gems ch. 7, as intersectSphere) and the stable pair of roots; both roots are
/// tried (a ray from inside the tube meets its far side). d need not be unit length.
inline std::optional<CylinderHit> intersectCylinder(const CylinderShape& s, const Vec3d& o,
                                                    const Vec3d& d, double tMin, double tMax) {
  const Vec3d a = s.axis();
  const double h = s.height();
  std::optional<CylinderHit> best;
  const Vec3d w = o - s.p0;
  const Vec3d wp = w - a * dot(w, a), dp = d - a * dot(d, a); // across the axis
  const double qa = dot(dp, dp);
  if (qa > 0) {
    const double b = -dot(wp, dp);
    const Vec3d l = wp + dp * (b / qa); // closest approach to the axis
    const double disc = qa * (s.radius * s.radius - dot(l, l));
    if (disc >= 0) {
      const double c = dot(wp, wp) - s.radius * s.radius;
      const double q = b + std::copysign(std::sqrt(disc), b);
      double t0 = q == 0 ? 0 : c / q, t1 = q == 0 ? 0 : q / qa;
      if (t0 > t1) std::swap(t0, t1);
      for (const double t : {t0, t1}) {
        if (!(t > tMin && t < tMax)) continue;
        const double z = dot(w + d * t, a);
        if (z >= 0 && z <= h) {
          best = CylinderHit{t, CylinderPart::Side};
          break;
        }
      }
    }
  }
  if (s.capped)
    for (const CylinderPart part : {CylinderPart::Base, CylinderPart::Top})
      if (const auto t = intersectDisk(s.cap(part), o, d, tMin, best ? best->t : tMax))
        best = CylinderHit{*t, part};
  return best;
}

/// The cylinder kind.
struct CylinderShapeKind {
  static constexpr const char* kName = "cylinder";
  static constexpr const char* kDoc =
      "a cylinder around the segment p0 -> p1, open or capped by two disks (exact "
      "double-precision intersection); as a light every part emits, sampled by area";
  static constexpr bool kHoldsMedium = false;
  /// Its parameters.
  static std::span<const ShapeParameter> parameters() {
    static const ShapeParameter p[] = {
        {differentiable({"p0", ParamType::Point, "scene units", nullptr, "the centre of one end",
                         "0, 0, 0", "", "an end's centre x, y, z"})},
        {differentiable({"p1", ParamType::Point, "scene units", nullptr,
                         "the centre of the other end", "0, 1, 0", "", "an end's centre x, y, z"})},
        {differentiable(
            {"radius", ParamType::Number, "scene units", &kRadiusRange, "its radius", "0.5"})},
        {{"capped", ParamType::Name, "", nullptr,
          "true: closed by a disk at each end; false (the default): an open tube", "true"},
         false,
         false,
         [](const ParamValue& v) -> const char* {
           const std::string& s = std::get<std::string>(v);
           return s == "true" || s == "false" ? nullptr : "capped true or false";
         }},
    };
    return p;
  }
  /// Equal ends make no cylinder.
  static std::optional<ShapeProblem> problem(const ParameterSet& p) {
    if (length(*p.get<Vec3d>("p1") - *p.get<Vec3d>("p0")) > 0) return std::nullopt;
    return ShapeProblem{"a cylinder whose ends p0 and p1 differ", "equal ends"};
  }
  /// Its primitive, from checked parameters.
  static CylinderShape build(const ParameterSet& p, const ShapeInputs&) {
    const std::string* capped = p.get<std::string>("capped");
    return {*p.get<Vec3d>("p0"), *p.get<Vec3d>("p1"), *p.number("radius"),
            capped && *capped == "true"};
  }
};

} // namespace nx
