#pragma once
// Sampling a triangle by the solid angle it subtends at a point (Arvo 1995), for area lights.

#include <algorithm>
#include <cmath>

#include "accel/shapes.h"
#include "core/sampler.h"

namespace nx {

/// Solid angles below this are never sampled by solid angle (the spherical construction loses
/// digits there; kSphericalSamplingFrom keeps far smaller triangles by area anyway).
inline constexpr double kMinSphericalSolidAngle = 1e-6;
/// Solid angles above this (a point nearly on the triangle's plane, inside it) are sampled by
/// area too: the spherical triangle's angles approach pi there.
inline constexpr double kMaxSphericalSolidAngle = 6.22;

/// A triangle seen from a point: unit directions to its corners and the solid angle it
/// subtends there (sr).
struct SphericalTriangle {
  Vec3d a, b, c;         ///< unit directions from the point to the corners
  double solidAngle = 0; ///< 0 for a degenerate or edge-on triangle
};

/// The solid angle of a triangle of unit corner directions (Van Oosterom & Strackee 1983):
/// tan(Omega / 2) = |a . (b x c)| / (1 + a . b + b . c + c . a).
inline double sphericalTriangleArea(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double det = std::abs(dot(a, cross(b, c)));
  const double den = 1 + dot(a, b) + dot(b, c) + dot(c, a);
  return 2 * std::atan2(det, den);
}

/// Triangle t seen from p; solidAngle 0 where a corner is p itself.
inline SphericalTriangle sphericalTriangle(const TriangleShape& t, const Vec3d& p) {
  SphericalTriangle s;
  const Vec3d da = t.a - p, db = t.b - p, dc = t.c - p;
  const double la = length(da), lb = length(db), lc = length(dc);
  if (!(la > 0) || !(lb > 0) || !(lc > 0)) return s;
  s.a = da * (1 / la), s.b = db * (1 / lb), s.c = dc * (1 / lc);
  s.solidAngle = sphericalTriangleArea(s.a, s.b, s.c);
  if (!std::isfinite(s.solidAngle)) s.solidAngle = 0;
  return s;
}

/// True when sampling by solid angle applies (see the two bounds above).
inline bool sampledBySolidAngle(double solidAngle) {
  return solidAngle >= kMinSphericalSolidAngle && solidAngle <= kMaxSphericalSolidAngle;
}

/// The solid angle of triangle t from p estimated at its centroid, A |cos| / d^2: cheap, for
/// deciding whether the exact construction is worth its cost.
inline double estimatedSolidAngle(const TriangleShape& t, const Vec3d& p) {
  const Vec3d nd = cross(t.b - t.a, t.c - t.a); // |nd| = 2 A
  const Vec3d d = (t.a + t.b + t.c) * (1.0 / 3) - p;
  const double d2 = dot(d, d);
  return d2 > 0 ? 0.5 * std::abs(dot(nd, d)) / (d2 * std::sqrt(d2)) : INFINITY;
}

/// Triangles smaller than this from the shading point (estimatedSolidAngle, sr) are sampled by
/// area: there the two densities differ by a few percent and solid-angle sampling costs more
/// than it saves (docs/performance.md, "Triangle lights by solid angle").
inline constexpr double kSphericalSamplingFrom = 0.01;

/// Whether triangle t is sampled by solid angle from p; then st is it seen from p (`known`, if
/// given, is it already).
inline bool worthSphericalSampling(const TriangleShape& t, const Vec3d& p, SphericalTriangle& st,
                                   const SphericalTriangle* known = nullptr) {
  if (estimatedSolidAngle(t, p) < kSphericalSamplingFrom) return false;
  st = known ? *known : sphericalTriangle(t, p);
  return sampledBySolidAngle(st.solidAngle);
}

/// Component of v orthogonal to unit vector n, made unit; false if v is (nearly) along n.
inline bool unitOrthogonal(const Vec3d& v, const Vec3d& n, Vec3d& out) {
  const Vec3d o = v - n * dot(v, n);
  const double l = length(o);
  if (!(l > 1e-300)) return false;
  out = o * (1 / l);
  return true;
}

/// A direction uniform in solid angle over the spherical triangle from u in [0, 1)^2 (Arvo
/// 1995, "Stratified sampling of spherical triangles"): u.u picks the sub-triangle of area
/// u.u Omega (its new corner c' on arc ac), u.v the point along the arc from b to c'. False
/// for a degenerate triangle. Only the angle alpha at a enters, through its cosine and sine
/// (no inverse trigonometry), and Omega is the Van Oosterom-Strackee value pdfs use.
inline bool sampleSphericalTriangle(const SphericalTriangle& s, Sample2 u, Vec3d& w) {
  Vec3d towardsB, towardsC;
  if (!(s.solidAngle > 0) || !unitOrthogonal(s.b, s.a, towardsB) ||
      !unitOrthogonal(s.c, s.a, towardsC))
    return false;
  const double cosAlpha = std::clamp(dot(towardsB, towardsC), -1.0, 1.0);
  const double sinAlpha = length(cross(towardsB, towardsC));
  if (!(sinAlpha > 0)) return false;
  // The sub-triangle a b c' of area u.u Omega: c' from Arvo's closed form for cos(arc a c'),
  // with phi = subArea - alpha expanded by the angle-difference identities.
  const double subArea = static_cast<double>(u.u) * s.solidAngle;
  const double sinS = std::sin(subArea), cosS = std::cos(subArea);
  const double sinPhi = sinS * cosAlpha - cosS * sinAlpha;
  const double cosPhi = cosS * cosAlpha + sinS * sinAlpha;
  const double cosC = dot(s.a, s.b);
  const double uu = cosPhi - cosAlpha, vv = sinPhi + sinAlpha * cosC;
  const double den = (vv * sinPhi + uu * cosPhi) * sinAlpha;
  double q = den != 0 ? ((vv * cosPhi - uu * sinPhi) * cosAlpha - vv) / den : 1.0;
  q = std::clamp(q, -1.0, 1.0);
  const Vec3d cPrime = s.a * q + towardsC * std::sqrt(std::max(0.0, 1 - q * q));
  // The point at cos(angle to b) = z on the arc from b to c', z uniform in [cos(b c'), 1].
  const double z = 1 - static_cast<double>(u.v) * (1 - dot(cPrime, s.b));
  Vec3d towardsCPrime;
  if (!unitOrthogonal(cPrime, s.b, towardsCPrime)) {
    w = s.b; // c' is b: the sub-triangle has no width
    return true;
  }
  w = s.b * z + towardsCPrime * std::sqrt(std::max(0.0, 1 - z * z));
  return true;
}

/// The point u of [0, 1)^2 that sampleSphericalTriangle maps to direction w (a unit direction
/// inside the triangle): u.u the share of the area of the sub-triangle a b c', c' where the
/// great circle through b and w meets arc ac, u.v from w's angle to b. Clamped into [0, 1]^2.
inline Sample2 invertSphericalTriangleSample(const SphericalTriangle& s, const Vec3d& w) {
  const Vec3d bw = cross(s.b, w), ac = cross(s.a, s.c);
  Vec3d cPrime = cross(bw, ac);
  const double l = length(cPrime);
  if (!(l > 1e-300) || !(s.solidAngle > 0)) return {0, 0}; // w is b: any u.u, u.v = 0
  cPrime = cPrime * (1 / l);
  if (dot(cPrime, s.a + s.c) < 0) cPrime = cPrime * -1.0;
  const double sub = sphericalTriangleArea(s.a, s.b, cPrime);
  const double u0 = std::clamp(sub / s.solidAngle, 0.0, 1.0);
  const double den = 1 - dot(cPrime, s.b);
  const double u1 = den > 0 ? std::clamp((1 - dot(w, s.b)) / den, 0.0, 1.0) : 0.0;
  return {static_cast<float>(std::min(u0, 0.99999994)),
          static_cast<float>(std::min(u1, 0.99999994))};
}

/// A bilinear density on [0, 1]^2 with values proportional to w00, w10, w01, w11 at its
/// corners (u, v) = (0, 0), (1, 0), (0, 1), (1, 1), all positive.
struct BilinearDensity {
  double w00 = 1, w10 = 1, w01 = 1, w11 = 1;
  /// Density at u (integrates to 1 over the square).
  double pdf(Sample2 u) const {
    const double x = u.u, y = u.v;
    return 4 * ((1 - x) * (1 - y) * w00 + x * (1 - y) * w10 + (1 - x) * y * w01 + x * y * w11) /
           (w00 + w10 + w01 + w11);
  }
  /// A point with this density from uniform u: v from its marginal, then u given v (each a
  /// linear density, inverted in closed form).
  Sample2 sample(Sample2 u) const {
    const double y = sampleLinear(u.v, w00 + w10, w01 + w11);
    const double x = sampleLinear(u.u, (1 - y) * w00 + y * w01, (1 - y) * w10 + y * w11);
    return {static_cast<float>(std::min(x, 0.99999994)),
            static_cast<float>(std::min(y, 0.99999994))};
  }
  /// x in [0, 1] with density proportional to (1 - x) a + x b: the root of its CDF, written
  /// without cancellation.
  static double sampleLinear(double xi, double a, double b) {
    if (a == b) return xi;
    const double x = xi * (a + b) / (a + std::sqrt(std::max(0.0, a * a + xi * (b * b - a * a))));
    return std::clamp(x, 0.0, 1.0);
  }
};

/// The cosine warp for a receiver of normal n (pbrt-v4 uses one alike): a bilinear density
/// over sampleSphericalTriangle's square whose corners carry |cos| between n and the corners
/// they map to ((0, v = 0) and (1, 0) map to b, (0, 1) to a, (1, 1) to c), at least 0.01, so
/// directions are drawn roughly in proportion to the projected solid angle.
inline BilinearDensity cosineWarp(const SphericalTriangle& s, const Vec3d& n) {
  const auto c = [&](const Vec3d& w) { return std::max(0.01, std::abs(dot(n, w))); };
  return {c(s.b), c(s.b), c(s.a), c(s.c)};
}

/// The cosine warp of a receiver of shading normal n over the square of spherical shape s (a
/// SphericalTriangle or SphericalRectangle): draws u through it and returns its density there;
/// without a receiver (n zero) u is kept and the density is 1.
template <class Spherical>
double applyCosineWarp(const Spherical& s, const Vec3& n, Sample2& u) {
  if (n == Vec3()) return 1;
  const BilinearDensity density = cosineWarp(s, Vec3d(n));
  u = density.sample(u);
  return density.pdf(u);
}

} // namespace nx
