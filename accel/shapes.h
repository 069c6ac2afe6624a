#pragma once
// Analytic shapes and their exact intersection routines (double precision).

#include <cmath>
#include <optional>

#include "core/vec3.h"

namespace nx {

/// A sphere.
struct SphereShape {
  Vec3d center;
  double radius = 1;
};

/// An infinite plane: the points p with dot(normal, p) = distance; normal is unit length.
struct PlaneShape {
  Vec3d normal{0, 1, 0};
  double distance = 0;
};

/// A triangle with vertices a, b, c (front face counter-clockwise seen from its normal
/// (b - a) x (c - a)).
struct TriangleShape {
  Vec3d a, b, c;
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

} // namespace nx
