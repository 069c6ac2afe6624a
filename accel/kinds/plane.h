#pragma once
// An infinite plane, <plane><normal>x, y, z</normal><distance>d</distance>: the points p with
// dot(normal, p) = d. Intersected analytically outside the BVH (accel/geometry_scene.h says
// why); as an emitter it is reached by BSDF sampling only (it has no finite area to sample).

#include <cmath>
#include <optional>

#include "accel/shape_schema.h"
#include "core/vec3.h"

namespace nx {

/// An infinite plane: the points p with dot(normal, p) = distance; normal is unit length.
struct PlaneShape {
  Vec3d normal{0, 1, 0};
  double distance = 0;
  /// Every field compared (the geometry cache reuses a BVH only for equal shapes).
  bool operator==(const PlaneShape&) const = default;
};

/// Ray parameter where o + t d meets the plane's infinite extension: may be negative,
/// infinite or NaN (a ray parallel to the plane), for branch-free callers.
inline double planeDistance(const PlaneShape& p, const Vec3d& o, const Vec3d& d) {
  return (p.distance - dot(p.normal, o)) / dot(p.normal, d);
}

/// Ray parameter t in (tMin, tMax) where o + t d meets the plane, if any.
inline std::optional<double> intersectPlane(const PlaneShape& p, const Vec3d& o, const Vec3d& d,
                                            double tMin, double tMax) {
  const double t = planeDistance(p, o, d); // inf or NaN when parallel: both comparisons fail
  if (t > tMin && t < tMax) return t;
  return std::nullopt;
}

/// The plane kind.
struct PlaneShapeKind {
  static constexpr const char* kName = "plane";
  static constexpr const char* kDoc =
      "an infinite plane dot(normal, p) = distance (normal normalised), exact to the horizon";
  static constexpr bool kHoldsMedium = false;
  /// Its parameters.
  static std::span<const ShapeParameter> parameters() {
    static const ShapeParameter p[] = {
        {{"normal", ParamType::Point, "1", nullptr, "its normal (any length but zero)", "0, 1, 0",
          "", "a plane normal x, y, z"},
         true,
         false,
         [](const ParamValue& v) -> const char* {
           return isNonZero(std::get<Vec3d>(v)) ? nullptr : "a non-zero plane normal";
         }},
        {{"distance", ParamType::Number, "scene units", &kPlaneDistanceRange,
          "its signed distance from the origin along the unit normal", "0"}},
    };
    return p;
  }
  /// Nothing beyond each value's checks.
  static std::optional<ShapeProblem> problem(const ParameterSet&) { return std::nullopt; }
  /// Its primitive, from checked parameters (the normal made unit length).
  static PlaneShape build(const ParameterSet& p, const ShapeInputs&) {
    return {normalizeAnyLength(*p.get<Vec3d>("normal")), *p.number("distance")};
  }
};

} // namespace nx
