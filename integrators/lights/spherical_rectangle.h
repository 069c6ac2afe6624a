#pragma once
// Sampling a rectangle by the solid angle it subtends at a point: Urena, Fajardo & King, "An
// Area-Preserving Parametrization for Spherical Rectangles" (EGSR 2013), with its inverse for
// densities at BSDF-sampled hits and the bilinear cosine warp of spherical_triangle.h.

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/math_util.h"
#include "core/triangle_mesh.h"
#include "integrators/lights/spherical_triangle.h"

namespace nx {

/// A rectangle: corner + s edgeX + t edgeY for s, t in [0, 1], edgeX perpendicular to edgeY.
struct Rectangle {
  Vec3d corner, edgeX, edgeY;
};

/// The rectangle a mesh of two triangles forms, when it does (four distinct corners, the two
/// triangles sharing a diagonal, the diagonals of equal length bisecting each other: a
/// rectangle to float rounding); nothing otherwise (a parallelogram, a kite, more triangles).
inline std::optional<Rectangle> rectangleOf(const TriangleMesh& m) {
  if (m.triangleCount() != 2) return std::nullopt;
  const TriangleShape t0 = m.corners(0), t1 = m.corners(1);
  const Vec3d a[3] = {t0.a, t0.b, t0.c}, b[3] = {t1.a, t1.b, t1.c};
  // The corner of each triangle the other does not have; the other two are the diagonal.
  int onlyA = -1, onlyB = -1, shared = 0;
  for (int i = 0; i < 3; ++i) {
    bool inB = false, inA = false;
    for (int j = 0; j < 3; ++j) inB = inB || a[i] == b[j], inA = inA || b[i] == a[j];
    if (!inB) onlyA = onlyA < 0 ? i : 3;
    if (inA) ++shared;
    if (!inA) onlyB = onlyB < 0 ? i : 3;
  }
  if (shared != 2 || onlyA < 0 || onlyA > 2 || onlyB < 0 || onlyB > 2) return std::nullopt;
  const Vec3d p = a[onlyA], q = b[onlyB];
  const Vec3d d1 = a[(onlyA + 1) % 3], d2 = a[(onlyA + 2) % 3];
  // Float corners: a rectangle's diagonals agree to a few roundings of its coordinates.
  const double diagonal = length(q - p);
  const double magnitude = std::max(
      {std::abs(p.x), std::abs(p.y), std::abs(p.z), std::abs(q.x), std::abs(q.y), std::abs(q.z)});
  const double tolerance = 1e-6 * diagonal + 8 * 0x1p-24 * magnitude;
  if (!(diagonal > 0) || length((p + q) * 0.5 - (d1 + d2) * 0.5) > tolerance ||
      std::abs(length(d2 - d1) - diagonal) > tolerance)
    return std::nullopt;
  const Rectangle r{p, d1 - p, d2 - p};
  if (!(length(cross(r.edgeX, r.edgeY)) > 0)) return std::nullopt;
  return r;
}

/// A rectangle's orthonormal frame (x, y along its edges, z = x cross y) and edge lengths,
/// computed once per light.
struct RectangleFrame {
  Vec3d corner, x, y, z;
  double lengthX = 0, lengthY = 0;
};

/// The frame of rectangle r (made orthonormal: its edges are perpendicular to float rounding).
inline RectangleFrame frameOf(const Rectangle& r) {
  RectangleFrame f;
  f.corner = r.corner;
  f.lengthX = length(r.edgeX);
  f.x = r.edgeX * (1 / f.lengthX);
  const Vec3d yPart = r.edgeY - f.x * dot(r.edgeY, f.x);
  f.y = yPart * (1 / length(yPart));
  f.lengthY = dot(r.edgeY, f.y);
  f.z = cross(f.x, f.y);
  return f;
}

/// A rectangle seen from a point o, in Urena et al.'s local frame (x, y along its edges, z
/// normal to it with the rectangle at z0 < 0): what sampling and its inverse need.
struct SphericalRectangle {
  Vec3d o, x, y, z;          ///< the point and the frame (unit vectors)
  double x0, x1, y0, y1, z0; ///< the rectangle [x0, x1] x [y0, y1] at height z0
  double b0, b1;             ///< n0.z and n2.z of the paper (planes through o and edges y0, y1)
  double k;                  ///< 2 pi - gamma2 - gamma3 of the paper
  double solidAngle = 0;     ///< 0 when o lies in the rectangle's plane
};

/// The sum a + b of two angles in [0, pi] from their cosines (in [0, 2 pi): one atan2 instead
/// of two inverse cosines).
inline double angleSum(double cosA, double cosB) {
  const double sinA = std::sqrt(std::max(0.0, 1 - cosA * cosA));
  const double sinB = std::sqrt(std::max(0.0, 1 - cosB * cosB));
  const double sum = std::atan2(sinA * cosB + cosA * sinB, cosA * cosB - sinA * sinB);
  return sum < 0 ? sum + 2 * kPi : sum;
}

/// gamma0 + gamma1 of Urena et al. for the rectangle [x0, x] x [y0, y1] at height z0: the
/// angles between the planes through o and its edges meet in closed form, the planes' normals
/// being n0 ~ (0, z0, -y0), n1 ~ (-z0, 0, x), n2 ~ (0, -z0, y1).
inline double firstAngles(double x, double y0, double y1, double z0, double l0, double l2) {
  const double l1 = std::sqrt(z0 * z0 + x * x);
  return angleSum(std::clamp(x * y0 / (l0 * l1), -1.0, 1.0),
                  std::clamp(-x * y1 / (l1 * l2), -1.0, 1.0));
}

/// The rectangle of frame f seen from o; solidAngle 0 where o lies in its plane.
inline SphericalRectangle sphericalRectangle(const RectangleFrame& f, const Vec3d& o) {
  SphericalRectangle s;
  s.o = o;
  s.x = f.x, s.y = f.y, s.z = f.z;
  const Vec3d d = f.corner - o;
  s.z0 = dot(d, s.z);
  if (s.z0 > 0) s.z = -s.z, s.z0 = -s.z0;
  s.x0 = dot(d, s.x), s.y0 = dot(d, s.y);
  s.x1 = s.x0 + f.lengthX, s.y1 = s.y0 + f.lengthY;
  if (!(s.z0 < 0) || !(f.lengthX > 0) || !(f.lengthY > 0)) return s;
  const double z2 = s.z0 * s.z0;
  const double l0 = std::sqrt(z2 + s.y0 * s.y0), l2 = std::sqrt(z2 + s.y1 * s.y1),
               l3 = std::sqrt(z2 + s.x0 * s.x0);
  s.b0 = -s.y0 / l0, s.b1 = s.y1 / l2;
  // gamma2 + gamma3: cos gamma2 = x0 y1 / (l2 l3), cos gamma3 = -x0 y0 / (l3 l0).
  s.k = 2 * kPi - angleSum(std::clamp(s.x0 * s.y1 / (l2 * l3), -1.0, 1.0),
                           std::clamp(-s.x0 * s.y0 / (l3 * l0), -1.0, 1.0));
  s.solidAngle = firstAngles(s.x1, s.y0, s.y1, s.z0, l0, l2) - s.k;
  if (!std::isfinite(s.solidAngle) || s.solidAngle < 0) s.solidAngle = 0;
  return s;
}

/// Rectangle r seen from o (its frame made on the way).
inline SphericalRectangle sphericalRectangle(const Rectangle& r, const Vec3d& o) {
  return sphericalRectangle(frameOf(r), o);
}

/// The point of the rectangle at (x, y) of the local frame, in world coordinates.
inline Vec3d rectanglePoint(const SphericalRectangle& s, double x, double y) {
  return s.o + s.x * x + s.y * y + s.z * s.z0;
}

/// The point of the rectangle whose direction from o is uniform in solid angle, from u in
/// [0, 1)^2 (Urena et al. 2013, section 3): u.u the share of the sub-rectangle [x0, xu] of the
/// solid angle, u.v the height along the chord at xu. False where the rectangle is not seen.
inline bool sampleSphericalRectangle(const SphericalRectangle& s, Sample2 u, Vec3d& point) {
  if (!(s.solidAngle > 0)) return false;
  const double au = static_cast<double>(u.u) * s.solidAngle + s.k;
  const double sinAu = std::sin(au);
  double xu;
  if (sinAu == 0) {
    xu = 0; // the plane at au contains the normal through o
  } else {
    // The paper's cu = sign(fu) / sqrt(fu^2 + b0^2) and xu = -cu z0 / sqrt(1 - cu^2), as one
    // square root: xu = -sign(fu) z0 / sqrt(fu^2 + b0^2 - 1) (the chain of dependent roots and
    // divisions is most of a rectangle sample's time). Where fu^2 + b0^2 <= 1 (cu = +-1 to
    // rounding) the chord is at the rectangle's edge on fu's side.
    const double fu = (std::cos(au) * s.b0 - s.b1) / sinAu;
    const double q = fu * fu + s.b0 * s.b0 - 1;
    if (std::isinf(fu))
      xu = 0; // cu = 0
    else if (q > 0)
      xu = -std::copysign(1.0, fu) * s.z0 / std::sqrt(q);
    else
      xu = fu > 0 ? s.x1 : s.x0;
  }
  xu = std::clamp(xu, s.x0, s.x1);
  const double d2 = xu * xu + s.z0 * s.z0, d = std::sqrt(d2);
  const double h0 = s.y0 / std::sqrt(d2 + s.y0 * s.y0), h1 = s.y1 / std::sqrt(d2 + s.y1 * s.y1);
  const double hv = h0 + static_cast<double>(u.v) * (h1 - h0), hv2 = hv * hv;
  const double yv = hv2 < 1 - 1e-12 ? std::clamp(hv * d / std::sqrt(1 - hv2), s.y0, s.y1) : s.y1;
  point = rectanglePoint(s, xu, yv);
  return true;
}

/// The u of [0, 1)^2 that sampleSphericalRectangle maps to `point` (on the rectangle): u.u
/// the share of the solid angle of the sub-rectangle [x0, x], u.v from the point's height
/// along the chord. Clamped into [0, 1)^2.
inline Sample2 invertSphericalRectangleSample(const SphericalRectangle& s, const Vec3d& point) {
  if (!(s.solidAngle > 0)) return {0, 0};
  const Vec3d d = point - s.o;
  const double x = std::clamp(dot(d, s.x), s.x0, s.x1), y = std::clamp(dot(d, s.y), s.y0, s.y1);
  // The sub-rectangle [x0, x]'s solid angle over the whole's (its au less k).
  const double l0 = std::sqrt(s.z0 * s.z0 + s.y0 * s.y0), l2 = std::sqrt(s.z0 * s.z0 + s.y1 * s.y1);
  const double u0 =
      x > s.x0
          ? std::clamp((firstAngles(x, s.y0, s.y1, s.z0, l0, l2) - s.k) / s.solidAngle, 0.0, 1.0)
          : 0.0;
  const double d2 = x * x + s.z0 * s.z0;
  const double h0 = s.y0 / std::sqrt(d2 + s.y0 * s.y0), h1 = s.y1 / std::sqrt(d2 + s.y1 * s.y1);
  const double hy = y / std::sqrt(d2 + y * y);
  const double u1 = h1 > h0 ? std::clamp((hy - h0) / (h1 - h0), 0.0, 1.0) : 0.0;
  return {static_cast<float>(std::min(u0, 0.99999994)),
          static_cast<float>(std::min(u1, 0.99999994))};
}

/// The cosine warp of a receiver of normal n over sampleSphericalRectangle's square: corners
/// (0, 0), (1, 0), (0, 1), (1, 1) map to the rectangle's corners (x0, y0), (x1, y0), (x0, y1),
/// (x1, y1), weighted by |cos| between n and the directions to them, at least 0.01.
inline BilinearDensity cosineWarp(const SphericalRectangle& s, const Vec3d& n) {
  const Vec3d local(dot(n, s.x), dot(n, s.y), dot(n, s.z)); // n in the rectangle's frame
  const auto c = [&](double x, double y) {
    const Vec3d v(x, y, s.z0);
    return std::max(0.01, std::abs(dot(local, v)) / length(v));
  };
  return {c(s.x0, s.y0), c(s.x1, s.y0), c(s.x0, s.y1), c(s.x1, s.y1)};
}

/// The solid angle of the rectangle of frame f from p estimated at its centre, A |cos| / d^2.
inline double estimatedSolidAngle(const RectangleFrame& f, const Vec3d& p) {
  const Vec3d d = f.corner + f.x * (0.5 * f.lengthX) + f.y * (0.5 * f.lengthY) - p;
  const double d2 = dot(d, d);
  return d2 > 0 ? f.lengthX * f.lengthY * std::abs(dot(f.z, d)) / (d2 * std::sqrt(d2)) : INFINITY;
}

/// Whether the rectangle of frame f is sampled by solid angle from p (the thresholds of
/// triangles); then s is it seen from p.
inline bool worthSphericalSampling(const RectangleFrame& f, const Vec3d& p, SphericalRectangle& s) {
  if (estimatedSolidAngle(f, p) < kSphericalSamplingFrom) return false;
  s = sphericalRectangle(f, p);
  return sampledBySolidAngle(s.solidAngle);
}

} // namespace nx
