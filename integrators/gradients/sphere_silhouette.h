#pragma once
// A sphere's silhouette seen from a point: the circle where the lines from the point touch it
// (where visibility changes as the sphere or the point moves: the boundary terms of shape
// derivatives sample it, primary_boundary.h and the path tracer's direction boundary).

#include <cmath>

#include "accel/kinds/sphere.h"
#include "core/vec3.h"

namespace nx {

/// The silhouette of a sphere seen from a point: the circle of tangent points, centre q,
/// radius rho, in the plane spanned by the unit vectors u, v.
struct SphereSilhouette {
  Vec3d q, u, v;
  double rho = 0;
  /// The tangent point at angle a.
  Vec3d at(double a) const { return q + (u * std::cos(a) + v * std::sin(a)) * rho; }
  /// d at / d a.
  Vec3d tangent(double a) const { return (u * -std::sin(a) + v * std::cos(a)) * rho; }
};

/// The silhouette of `s` seen from `o`; false when o is inside the sphere or on it.
inline bool sphereSilhouette(const SphereShape& s, const Vec3d& o, SphereSilhouette& out) {
  const Vec3d a = s.center - o;
  const double d2 = dot(a, a), r2 = s.radius * s.radius;
  if (!(d2 > r2 * (1 + 1e-9))) return false;
  const double k = 1 - r2 / d2;
  out.q = o + a * k;
  out.rho = s.radius * std::sqrt(k);
  const Vec3d w = normalize(a);
  const Vec3d helper = std::abs(w.x) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
  out.u = normalize(cross(w, helper));
  out.v = cross(w, out.u);
  return true;
}

} // namespace nx
