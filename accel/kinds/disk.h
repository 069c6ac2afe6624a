#pragma once
// A disk, <disk><center/><normal/><radius/>: Embree user geometry intersected exactly in double
// precision (the plane's parameter, then the distance from the centre); both faces emit when
// it is a light, which the light sampler samples uniformly by area (MIS with the BSDF).

#include <cmath>
#include <optional>

#include "accel/primitive.h"
#include "accel/shape_schema.h"
#include "core/concentric_disk.h"
#include "core/math_util.h"
#include "core/ray_offset.h"
#include "core/vec3.h"

namespace nx {

struct DiskShape;
/// Ray parameter where a ray meets the disk (defined below).
inline std::optional<double> intersectDisk(const DiskShape& s, const Vec3d& o, const Vec3d& d,
                                           double tMin, double tMax);
/// Half-extents of the box around a circle of radius r with unit normal n (defined below).
inline Vec3d circleExtent(const Vec3d& n, double r);

/// A disk: the points of the plane through `center` with unit normal `normal` within `radius`
/// of the centre. Its front face is the normal's side; uv are polar: u = phi / 2 pi around the
/// normal (from AxisFrame::s), v = distance / radius.
struct DiskShape {
  Vec3d center;
  Vec3d normal{0, 1, 0};
  double radius = 1;
  bool operator==(const DiskShape&) const = default;
  /// Its box (circleExtent around the centre).
  BoundingBox bounds() const {
    const Vec3d e = circleExtent(normal, radius);
    return {center - e, center + e};
  }
  /// Its hit (intersectDisk).
  std::optional<PrimitiveHit> intersect(const Vec3d& o, const Vec3d& d, double tMin,
                                        double tMax) const {
    const auto t = intersectDisk(*this, o, d, tMin, tMax);
    return t ? std::optional(PrimitiveHit{*t, 0}) : std::nullopt;
  }
  /// The point exactly onto the disk's plane, its front normal, polar uv and the tangent of u.
  void fillHit(const Vec3d& o, const Vec3d& d, double t, uint32_t, SurfaceHit& hit) const {
    const Vec3d q = o + d * t - center;
    const Vec3d inPlane = q - normal * dot(normal, q);
    hit.p = Vec3(center + inPlane);
    hit.ng = hit.ns = Vec3(normal);
    const AxisFrame f = AxisFrame::of(normal);
    const double x = dot(inPlane, f.s), y = dot(inPlane, f.t);
    hit.u = turnFraction(y, x);
    hit.v = static_cast<float>(std::min(1.0, length(inPlane) / radius));
    const Vec3d dpdu = (f.t * x - f.s * y) * (2 * kPi);
    hit.dpdu = length(dpdu) > 0 ? Vec3(dpdu) : Vec3(f.s);
    hit.pError = roundingError(hit.p);
  }
  /// Flat: nothing turns.
  Vec3 normalTurning(const SurfaceHit&, const Vec3&) const { return {}; }
  /// Its area.
  double area() const { return kPi * radius * radius; }
  /// A point uniformly by area (the concentric map: density 1 / area).
  AreaSample sampleArea(Sample2 u) const {
    float x, y;
    sampleConcentricDisk(u, x, y);
    const AxisFrame f = AxisFrame::of(normal);
    return {center + (f.s * double(x) + f.t * double(y)) * radius, normal, 0};
  }
  /// Flat: its front normal.
  std::optional<Vec3d> facing() const { return normal; }
  /// Its rim, seen from a point off its plane.
  void outlines(const Vec3d& o, OutlineCurves& out) const {
    if (std::abs(dot(o - center, normal)) > 1e-9 * radius)
      out.add(OutlineCurve::circle(center, normal, radius, 0, radius));
  }
  /// The point at the same polar coordinates on `moved` (turned with its normal by the
  /// shortest rotation, scaled with its radius).
  CarriedPoint carry(const DiskShape& moved, const Vec3d& x, uint32_t) const {
    const Vec3d q = x - center, inPlane = q - normal * dot(normal, q);
    return {moved.center + rotateBetween(normal, moved.normal, inPlane) * (moved.radius / radius),
            moved.normal};
  }
  /// Flat: its light never falls on itself.
  static constexpr SelfLighting kSelfLighting = SelfLighting::Never;
  /// Both faces emit: 2 pi times its area.
  double fluxPerRadiance() const { return 2 * kPi * area(); }
  /// pi sin^2 of its half-angle seen from distance d on its axis: pi r^2 / (r^2 + d^2).
  double axialIrradiancePerRadiance(double d, const std::string&) const {
    return kPi * radius * radius / (radius * radius + d * d);
  }
};

/// Ray parameter t in (tMin, tMax) where o + t d meets the disk, if any (a ray in its plane
/// meets nothing). d need not be unit length.
inline std::optional<double> intersectDisk(const DiskShape& s, const Vec3d& o, const Vec3d& d,
                                           double tMin, double tMax) {
  const double denominator = dot(s.normal, d);
  if (denominator == 0) return std::nullopt;
  const double t = dot(s.normal, s.center - o) / denominator;
  if (!(t > tMin && t < tMax)) return std::nullopt;
  const Vec3d q = o + d * t - s.center;
  const Vec3d inPlane = q - s.normal * dot(s.normal, q);
  if (dot(inPlane, inPlane) > s.radius * s.radius) return std::nullopt;
  return t;
}

/// Half-extents of the box around a circle of radius r with unit normal n (r sqrt(1 - n_i^2)).
inline Vec3d circleExtent(const Vec3d& n, double r) {
  return {r * std::sqrt(std::max(0.0, 1 - n.x * n.x)), r * std::sqrt(std::max(0.0, 1 - n.y * n.y)),
          r * std::sqrt(std::max(0.0, 1 - n.z * n.z))};
}

/// The disk kind.
struct DiskShapeKind {
  static constexpr const char* kName = "disk";
  static constexpr const char* kDoc =
      "a flat disk (exact double-precision intersection); as a light both faces emit, sampled "
      "by area";
  static constexpr bool kHoldsMedium = false;
  /// Its parameters.
  static std::span<const ShapeParameter> parameters() {
    static const ShapeParameter p[] = {
        {differentiable({"center", ParamType::Point, "scene units", nullptr, "its centre",
                         "0, 1, 0", "", "a disk centre x, y, z"})},
        {differentiable({"normal", ParamType::Point, "1", nullptr,
                         "the direction its front face faces (normalised)", "0, -1, 0", "",
                         "a normal x, y, z"}),
         true, false,
         [](const ParamValue& v) -> const char* {
           return isNonZero(std::get<Vec3d>(v)) ? nullptr : "a non-zero disk normal";
         }},
        {differentiable(
            {"radius", ParamType::Number, "scene units", &kRadiusRange, "its radius", "0.5"})},
    };
    return p;
  }
  /// Nothing beyond each value's checks.
  static std::optional<ShapeProblem> problem(const ParameterSet&) { return std::nullopt; }
  /// Its primitive, from checked parameters.
  static DiskShape build(const ParameterSet& p, const ShapeInputs&) {
    return {*p.get<Vec3d>("center"), normalizeAnyLength(*p.get<Vec3d>("normal")),
            *p.number("radius")};
  }
};

} // namespace nx
