#pragma once
// A sphere, <sphere><center>x, y, z</center><radius>r</radius>: Embree user geometry,
// intersected exactly in double precision; it can hold a <medium>, and as an emitter the light
// sampler samples the cone it subtends.

#include <cmath>
#include <optional>

#include "accel/shape_schema.h"
#include "core/math_util.h"
#include "core/vec3.h"

namespace nx {

/// A sphere.
struct SphereShape {
  Vec3d center;
  double radius = 1;
  /// Every field compared (the geometry cache reuses a BVH only for equal shapes).
  bool operator==(const SphereShape&) const = default;
  /// Its area 4 pi r^2.
  double area() const { return 4 * kPi * radius * radius; }
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
