#pragma once
// Bounds of a cluster of emitters (a box, a cone of normals, a power) and the importance they
// bound at a shading point: Conty Estevez & Kulla, "Importance Sampling of Many Lights with
// Adaptive Tree Splitting" (HPG 2018), section 4. Used to choose among lights and among the
// triangles of an emitting mesh.

#include <algorithm>
#include <cmath>

#include "core/math_util.h"
#include "core/vec3.h"

namespace nx {

/// A cone of directions: unit axis and the cosine of its half-angle (-1: every direction).
struct DirectionCone {
  Vec3 axis{0, 0, 1};
  float cosSpread = 1; ///< cos(theta_o); 1 for one direction, -1 for the whole sphere
  /// The cone of every direction.
  static DirectionCone all() { return {{0, 0, 1}, -1}; }
};

/// The smallest cone (of the construction of Conty Estevez & Kulla 2018, Algorithm 1) holding
/// both cones.
inline DirectionCone unionOf(const DirectionCone& a, const DirectionCone& b) {
  if (a.cosSpread <= -1 || b.cosSpread <= -1) return DirectionCone::all();
  const double thetaA = std::acos(std::clamp(static_cast<double>(a.cosSpread), -1.0, 1.0));
  const double thetaB = std::acos(std::clamp(static_cast<double>(b.cosSpread), -1.0, 1.0));
  const double between = std::acos(std::clamp(static_cast<double>(dot(a.axis, b.axis)), -1.0, 1.0));
  if (std::min(between + thetaB, kPi) <= thetaA) return a; // b lies inside a
  if (std::min(between + thetaA, kPi) <= thetaB) return b;
  const double theta = 0.5 * (thetaA + between + thetaB);
  if (theta >= kPi) return DirectionCone::all();
  // a's axis turned towards b's by theta - thetaA, within the plane of both axes.
  const double turn = theta - thetaA;
  const Vec3d ad(a.axis), bd(b.axis);
  const Vec3d ortho = bd - ad * dot(ad, bd);
  const double len = length(ortho);
  if (!(len > 1e-12)) return DirectionCone::all(); // opposite axes
  const Vec3d axis = ad * std::cos(turn) + ortho * (std::sin(turn) / len);
  // Rounded outward slightly, so the union holds both cones despite the rounding above.
  return {Vec3(normalize(axis)), static_cast<float>(std::cos(std::min(kPi, theta + 1e-6)))};
}

/// cos(max(0, a - b)) from the cosines and sines of angles a, b in [0, pi].
inline float cosOfClampedDifference(float cosA, float sinA, float cosB, float sinB) {
  return cosA >= cosB ? 1.0f : cosA * cosB + sinA * sinB;
}

/// Emitters gathered in a box: the cone holding their normals (their axes: a spot's), how far
/// beyond its normal each emits (Conty Estevez & Kulla's theta_e: pi / 2 for diffuse emission,
/// 0 for a spot whose cone holds all its light) and their power (any common unit: the area
/// times a radiance).
struct LightBounds {
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  DirectionCone normals;
  float power = 0;
  float cosEmission = 0; ///< cos(theta_e): 0 for diffuse emission, 1 for a spot's cone
  bool twoSided = false; ///< the emitters' opposite faces emit too
  /// For flat emitters (triangles): a point o and the least signed distance from it to an
  /// emitter's plane along its normal, min over emitters of dot(n, x - o) for x on it. A point
  /// p lies behind every emitter's plane (sees no front face) when the largest dot(n, p - o),
  /// bounded by the normals' cone, is at most this: the test prunes most where o lies deep
  /// behind all the planes (a convex mesh's centroid). -infinity: no such test.
  Vec3 planeAnchor;
  float planeOffset = -INFINITY;

  /// Grows the box to hold p.
  void add(const Vec3& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  /// Centre of the box.
  Vec3 center() const { return (lo + hi) * 0.5f; }
};

/// LightBounds ready for queries (the render loop's form): centre and radius of the box's
/// bounding sphere, the cone's sine and cosine, the plane test's anchor. One cache line.
struct LightCluster {
  Vec3 center;                   ///< of the box
  float radius = 0;              ///< half the box's diagonal
  Vec3 axis{0, 0, 1};            ///< of the normals' cone
  float cosSpread = -1;          ///< cos(theta_o)
  float sinSpread = 0;           ///< sin(theta_o)
  float power = 0;               ///< as LightBounds::power
  Vec3 planeAnchor;              ///< LightBounds::planeAnchor
  float planeOffset = -INFINITY; ///< LightBounds::planeOffset
  float cosEmission = 0;         ///< LightBounds::cosEmission
  bool twoSided = false;         ///< LightBounds::twoSided

  LightCluster() = default;
  /// The cluster of bounds b.
  explicit LightCluster(const LightBounds& b)
      : center(b.center()), radius(length(b.hi - b.lo) * 0.5f), axis(b.normals.axis),
        cosSpread(std::clamp(b.normals.cosSpread, -1.0f, 1.0f)),
        sinSpread(std::sqrt(std::max(0.0f, 1 - cosSpread * cosSpread))), power(b.power),
        planeAnchor(b.planeAnchor), planeOffset(b.planeOffset), cosEmission(b.cosEmission),
        twoSided(b.twoSided) {}

  /// How much the cluster can send to point p (receiver normal n, or zero inside a medium):
  /// power cos(theta') |cos(theta_i')| / d^2 (Conty Estevez & Kulla 2018, eq. 3), where theta'
  /// is the least angle between an emitter's normal and a direction towards p (the angle to
  /// p's direction from the box's centre less the cone's spread theta_o and the angle theta_u
  /// the box's bounding sphere subtends at p) and theta_i' the least angle between +-n and a
  /// direction into that sphere. Zero only where no emitter of the cluster faces p: with
  /// bothFaces, emitters face both ways (the normals' cone and its opposite). From inside the
  /// sphere: power / radius^2. Emitters of cosEmission > 0 (spots) send nothing beyond
  /// theta_e: zero where theta' passes it (with a margin for rounding).
  float importance(const Vec3& p, const Vec3& n, bool bothFaces) const {
    // Written for latency: every square root is taken from squared lengths available at
    // once (sin^2 = 1 - cos^2 as (d^2 - a^2) / d^2), none waits for another.
    const Vec3 toP = p - center;
    const float d2 = dot(toP, toP), r2 = radius * radius;
    if (!(d2 > r2)) return r2 > 0 ? power / r2 : power / std::max(d2, 1e-30f);
    const float along = dot(axis, toP), across = n == Vec3() ? 0.0f : std::abs(dot(n, toP));
    const float d = std::sqrt(d2), invD = 1 / d;
    const float sinU = radius * invD, cosU = std::sqrt(d2 - r2) * invD;
    // theta' = theta - (theta_o + theta_u), psi = theta_o + theta_u by its sine and cosine.
    const float cosPsi = cosSpread * cosU - sinSpread * sinU;
    const float sinPsi = sinSpread * cosU + cosSpread * sinU;
    const float cosTheta = std::min(1.0f, (bothFaces ? std::abs(along) : along) * invD);
    const float sinTheta = std::sqrt(std::max(0.0f, d2 - along * along)) * invD;
    float cosPrime = 1; // theta within psi, or psi >= pi: some normal faces p head-on
    if (sinPsi >= 0 && cosTheta < cosPsi) cosPrime = cosTheta * cosPsi + sinTheta * sinPsi;
    // Every emitter turned away (theta' >= theta_e; pi / 2 for diffuse emission).
    if (!(cosPrime > 0) || cosPrime < cosEmission - 1e-6f) return 0;
    if (!bothFaces && behindAllPlanes(p)) return 0;
    float value = power * cosPrime * invD * invD;
    if (!(n == Vec3())) {
      const float cosI = std::min(1.0f, across * invD);
      const float sinI = std::sqrt(std::max(0.0f, d2 - across * across)) * invD;
      if (cosI < cosU) value *= cosI * cosU + sinI * sinU;
    }
    return value;
  }

  /// Whether p lies behind the planes of every emitter (LightBounds::planeOffset's test: the
  /// largest dot(m, p - anchor) over the normals' cone at most the offset, with a margin for
  /// rounding); false without the test.
  bool behindAllPlanes(const Vec3& p) const {
    if (!(planeOffset > -INFINITY)) return false;
    const Vec3 q = p - planeAnchor;
    const float q2 = dot(q, q), a = dot(axis, q);
    const float qLength = std::sqrt(q2), across = std::sqrt(std::max(0.0f, q2 - a * a));
    const float reach = a >= qLength * cosSpread ? qLength : a * cosSpread + across * sinSpread;
    return reach + 1e-5f * (qLength + std::abs(planeOffset)) <= planeOffset;
  }
};

/// The orientation measure M_Omega of emitters whose normals lie in a cone of half-angle
/// theta_o and which emit up to theta_e beyond their normal (Conty Estevez & Kulla 2018,
/// section 4.4): 2 pi (1 - cos theta_o) + pi / 2 (2 theta_w sin theta_o - cos(theta_o -
/// 2 theta_w) - 2 theta_o sin theta_o + cos theta_o), theta_w = min(theta_o + theta_e, pi).
/// From the cosines; diffuse emission (theta_e = pi / 2) in closed form without the inverse
/// cosine on the narrow side, the split heuristic's hot case.
inline double orientationMeasure(float cosSpread, float cosEmission) {
  const double cosO = std::clamp(static_cast<double>(cosSpread), -1.0, 1.0);
  const double sinO = std::sqrt(std::max(0.0, 1 - cosO * cosO));
  if (cosEmission == 0) {
    if (cosO >= 0) return 2 * kPi - kPi * cosO + 0.5 * kPi * kPi * sinO;
    return 2 * kPi * (1 - cosO) + kPi * (kPi - std::acos(cosO)) * sinO;
  }
  const double thetaO = std::acos(cosO);
  const double thetaE = std::acos(std::clamp(static_cast<double>(cosEmission), -1.0, 1.0));
  const double thetaW = std::min(thetaO + thetaE, kPi);
  return 2 * kPi * (1 - cosO) +
         0.5 * kPi * (2 * thetaW * sinO - std::cos(thetaO - 2 * thetaW) - 2 * thetaO * sinO + cosO);
}

/// The box's surface area: its measure M_A in the split heuristic (Conty Estevez & Kulla 2018,
/// section 4.4); 0 when empty.
inline double surfaceArea(const LightBounds& b) {
  if (b.lo.x > b.hi.x) return 0;
  const Vec3 e = b.hi - b.lo;
  const double x = e.x, y = e.y, z = e.z;
  return 2.0 * (x * y + y * z + z * x);
}

/// surfaceArea plus the squared diagonal: the measure for boxes of point lights, which may lie
/// on a line (a row of lamps: no area, yet an extent to split).
inline double boxMeasure(const LightBounds& b) {
  if (b.lo.x > b.hi.x) return 0;
  const Vec3 e = b.hi - b.lo;
  return surfaceArea(b) + static_cast<double>(dot(e, e));
}

/// Bounds of both clusters.
inline LightBounds unionOf(const LightBounds& a, const LightBounds& b) {
  if (!(a.power > 0) && a.lo.x > a.hi.x) return b;
  if (!(b.power > 0) && b.lo.x > b.hi.x) return a;
  LightBounds u;
  u.lo = {std::min(a.lo.x, b.lo.x), std::min(a.lo.y, b.lo.y), std::min(a.lo.z, b.lo.z)};
  u.hi = {std::max(a.hi.x, b.hi.x), std::max(a.hi.y, b.hi.y), std::max(a.hi.z, b.hi.z)};
  u.normals = unionOf(a.normals, b.normals);
  u.power = a.power + b.power;
  u.cosEmission = std::min(a.cosEmission, b.cosEmission);
  u.twoSided = a.twoSided || b.twoSided;
  // The planes' offsets from a's anchor: b's differ by at most the anchors' distance.
  u.planeAnchor = a.planeAnchor;
  u.planeOffset = std::min(a.planeOffset, b.planeOffset - length(b.planeAnchor - a.planeAnchor));
  return u;
}

} // namespace nx
