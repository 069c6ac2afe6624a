#pragma once
// One triangle, <triangle><vA/><vB/><vC/>: the scene's inline triangles are gathered into one
// Embree mesh; as an emitter the light sampler samples it by solid angle.

#include <optional>

#include "accel/shape_schema.h"
#include "core/triangle_mesh.h"
#include "core/vec3.h"

namespace nx {

/// Ray parameter t in (tMin, tMax) where o + t d meets the triangle (Moeller-Trumbore in
/// double precision), if any. Used as the independent reference in tests.
inline std::optional<double> intersectTriangle(const TriangleShape& tri, const Vec3d& o,
                                               const Vec3d& d, double tMin, double tMax) {
  const Vec3d e1 = tri.b - tri.a, e2 = tri.c - tri.a;
  const Vec3d pv = cross(d, e2);
  const double det = dot(e1, pv);
  if (det == 0) return std::nullopt;
  const double inv = 1.0 / det;
  const Vec3d tv = o - tri.a;
  const double u = dot(tv, pv) * inv;
  if (u < 0 || u > 1) return std::nullopt;
  const Vec3d qv = cross(tv, e1);
  const double v = dot(d, qv) * inv;
  if (v < 0 || u + v > 1) return std::nullopt;
  const double t = dot(e2, qv) * inv;
  if (t > tMin && t < tMax) return t;
  return std::nullopt;
}

/// The triangle kind.
struct TriangleShapeKind {
  static constexpr const char* kName = "triangle";
  static constexpr const char* kDoc =
      "one triangle vA, vB, vC (front face counter-clockwise seen from (vB - vA) x (vC - vA))";
  static constexpr bool kHoldsMedium = false;
  /// Its parameters.
  static std::span<const ShapeParameter> parameters() {
    static const ShapeParameter p[] = {
        {differentiable({"vA", ParamType::Point, "scene units", nullptr, "its first vertex",
                         "0, 0, 0", "", "a vertex x, y, z"})},
        {differentiable({"vB", ParamType::Point, "scene units", nullptr, "its second vertex",
                         "1, 0, 0", "", "a vertex x, y, z"})},
        {differentiable({"vC", ParamType::Point, "scene units", nullptr, "its third vertex",
                         "0, 1, 0", "", "a vertex x, y, z"})},
    };
    return p;
  }
  /// Collinear vertices make no triangle.
  static std::optional<ShapeProblem> problem(const ParameterSet& p) {
    const Vec3d a = *p.get<Vec3d>("vA"), b = *p.get<Vec3d>("vB"), c = *p.get<Vec3d>("vC");
    if (length(cross(b - a, c - a)) > 0) return std::nullopt;
    return ShapeProblem{"a triangle with non-zero area", "collinear vertices"};
  }
  /// Its primitive, from checked parameters.
  static TriangleShape build(const ParameterSet& p, const ShapeInputs&) {
    return {*p.get<Vec3d>("vA"), *p.get<Vec3d>("vB"), *p.get<Vec3d>("vC")};
  }
};

} // namespace nx
