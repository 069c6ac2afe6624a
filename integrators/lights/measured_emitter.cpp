#include "integrators/lights/measured_emitter.h"

#include <cmath>
#include <optional>
#include <variant>
#include <vector>

#include "accel/closed_mesh.h"
#include "core/error.h"
#include "core/math_util.h"

namespace nx {

namespace {

// The triangles of a flat or meshed emitter.
std::vector<TriangleShape> trianglesOf(const ShapeGeometry& g) {
  std::vector<TriangleShape> out;
  if (const auto* t = std::get_if<TriangleShape>(&g)) out.push_back(*t);
  if (const auto* m = std::get_if<TriangleMesh>(&g))
    for (size_t k = 0; k < m->triangleCount(); ++k) out.push_back(m->corners(k));
  return out;
}

} // namespace

double projectedSolidAngle(const TriangleShape& t, const Vec3d& x, const Vec3d& n) {
  const Vec3d v[3] = {normalize(t.a - x), normalize(t.b - x), normalize(t.c - x)};
  double sum = 0;
  for (int e = 0; e < 3; ++e) {
    const Vec3d& a = v[e];
    const Vec3d& b = v[(e + 1) % 3];
    const Vec3d c = cross(a, b);
    const double s = length(c);
    if (!(s > 0)) continue;
    sum += std::atan2(s, dot(a, b)) * dot(c / s, n);
  }
  return std::abs(sum) / 2;
}

double axialIrradiancePerRadiance(const ShapeGeometry& g, double d, const std::string& where) {
  if (std::holds_alternative<PlaneShape>(g))
    throw Error(where + ": expected an emitter of finite size for at=\"...\", found a plane");
  // An analytic primitive knows its own axis (or says it has none).
  const std::optional<double> primitive = std::visit(
      [&](const auto& shape) -> std::optional<double> {
        if constexpr (AnalyticPrimitive<std::decay_t<decltype(shape)>>)
          return shape.axialIrradiancePerRadiance(d, where);
        else
          return std::nullopt;
      },
      g);
  if (primitive) return *primitive;
  const std::vector<TriangleShape> tris = trianglesOf(g);
  // The axis: the normal through the area-weighted centroid; every triangle in its plane.
  Vec3d normalSum, centroid;
  double area = 0;
  for (const TriangleShape& t : tris) {
    const Vec3d c = cross(t.b - t.a, t.c - t.a);
    const double a = length(c) / 2;
    area += a;
    normalSum = normalSum + c;
    centroid = centroid + (t.a + t.b + t.c) * (a / 3);
  }
  if (!(area > 0))
    throw Error(where + ": expected an emitter with area for at=\"...\", found none");
  centroid = centroid / area;
  const Vec3d n = length(normalSum) > 0 ? normalize(normalSum) : Vec3d(0, 0, 0);
  bool flat = length(normalSum) > (1 - 1e-6) * 2 * area; // every triangle facing one way
  for (const TriangleShape& t : tris)
    for (const Vec3d& p : {t.a, t.b, t.c})
      flat = flat && std::abs(dot(p - centroid, n)) <= 1e-6 * std::sqrt(area);
  if (!flat)
    throw Error(where + ": expected a flat emitter for at=\"...\" (a triangle, a quad or a planar "
                        "mesh: its axis is the normal through its centroid), found a curved or "
                        "folded mesh (give its total flux with quantity=\"flux\")");
  const Vec3d x = centroid + n * d;
  double omega = 0;
  for (const TriangleShape& t : tris) omega += projectedSolidAngle(t, x, n * -1.0);
  return omega;
}

double fluxPerRadiance(const ShapeGeometry& g, const std::string& where) {
  if (std::holds_alternative<PlaneShape>(g))
    throw Error(where +
                ": expected an emitter of finite size for quantity=\"flux\", found a plane");
  // Both faces of flat and open shapes emit; a closed shape's inward light never leaves.
  const std::optional<double> primitive = std::visit(
      [&](const auto& shape) -> std::optional<double> {
        if constexpr (AnalyticPrimitive<std::decay_t<decltype(shape)>>)
          return shape.fluxPerRadiance();
        else
          return std::nullopt;
      },
      g);
  if (primitive) return *primitive;
  double area = 0;
  for (const TriangleShape& t : trianglesOf(g)) area += length(cross(t.b - t.a, t.c - t.a)) / 2;
  const auto* m = std::get_if<TriangleMesh>(&g);
  const bool closed = m && meshClosure(*m).closed;
  return (closed ? 1 : 2) * kPi * area;
}

} // namespace nx
