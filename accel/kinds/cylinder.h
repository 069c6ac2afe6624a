#pragma once
// A cylinder, <cylinder><p0/><p1/><radius/><capped/>: the tube of `radius` around the segment
// p0 -> p1, open or closed by two disks; Embree user geometry intersected exactly in double
// precision (the closest-approach quadratic, as for spheres, then the caps); as a light every
// part emits on both sides, sampled uniformly by area (MIS with the BSDF).

#include <cmath>
#include <optional>

#include "accel/kinds/disk.h"

namespace nx {

/// Which part of a cylinder a hit is on.
enum class CylinderPart : uint8_t { Side, Base, Top };

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
};

/// A hit on a cylinder: the ray parameter and the part.
struct CylinderHit {
  double t;
  CylinderPart part;
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
        {{"p0", ParamType::Point, "scene units", nullptr, "the centre of one end", "0, 0, 0", "",
          "an end's centre x, y, z"}},
        {{"p1", ParamType::Point, "scene units", nullptr, "the centre of the other end", "0, 1, 0",
          "", "an end's centre x, y, z"}},
        {{"radius", ParamType::Number, "scene units", &kRadiusRange, "its radius", "0.5"}},
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
