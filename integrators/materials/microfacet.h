#pragma once
// The GGX (Trowbridge-Reitz) microfacet distribution with anisotropic roughness, its Smith
// masking-shadowing, and sampling of the normals visible from a direction (Heitz 2018).
// Directions are in the local frame of the macro-surface: z along its normal, x along the
// tangent of alpha_x.

#include <algorithm>
#include <cmath>

#include "core/math_util.h"
#include "core/sampler.h"
#include "core/vec3.h"

namespace nx {

/// GGX with roughness alpha_x, alpha_y (slope widths along the local x and y axes).
struct GgxDistribution {
  float ax = 0, ay = 0;

  /// D(h): the density of micro-normals per unit projected area (Walter et al. 2007, eq. 33,
  /// anisotropic form of Heitz 2014, eq. 85); 0 below the macro-surface.
  float d(const Vec3& h) const {
    if (h.z <= 0) return 0;
    const float x = h.x / ax, y = h.y / ay;
    const float s = x * x + y * y + h.z * h.z;
    return 1.0f / (static_cast<float>(kPi) * ax * ay * s * s);
  }

  /// Smith's Lambda(w) (Heitz 2014, eq. 86): G1 = 1 / (1 + Lambda).
  float lambda(const Vec3& w) const {
    const float z2 = w.z * w.z;
    if (!(z2 > 0)) return INFINITY;
    const float a2 = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / z2;
    return 0.5f * (std::sqrt(1 + a2) - 1);
  }

  /// The derivatives of ln(D(h) G2(o, i)) with respect to ax and ay for a reflection from o to
  /// i (local frame, both above; h their half vector): what a rough conductor's f depends on
  /// its roughness by. ln D = -ln(pi ax ay) - 2 ln s, s = (hx/ax)^2 + (hy/ay)^2 + hz^2; G2 =
  /// 1 / (1 + Lambda(o) + Lambda(i)), d Lambda / d ax = ax wx^2 / (2 wz^2 sqrt(1 + a^2)).
  void logDerivatives(const Vec3& o, const Vec3& i, float& dax, float& day) const {
    const Vec3 h = normalize(o + i);
    const float x = h.x / ax, y = h.y / ay;
    const float s = x * x + y * y + h.z * h.z;
    dax = -1 / ax + 4 * x * x / (ax * s);
    day = -1 / ay + 4 * y * y / (ay * s);
    auto dLambda = [&](const Vec3& w, float& lx, float& ly) {
      const float z2 = w.z * w.z;
      const float a2 = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / z2;
      const float r = 2 * z2 * std::sqrt(1 + a2);
      lx = ax * w.x * w.x / r;
      ly = ay * w.y * w.y / r;
    };
    float ox, oy, ix, iy;
    dLambda(o, ox, oy);
    dLambda(i, ix, iy);
    const float g = 1 + lambda(o) + lambda(i);
    dax -= (ox + ix) / g;
    day -= (oy + iy) / g;
  }

  /// Masking of micro-normals seen from w.
  float g1(const Vec3& w) const { return 1.0f / (1 + lambda(w)); }

  /// Height-correlated masking-shadowing of the pair (Heitz 2014, eq. 99).
  float g2(const Vec3& wo, const Vec3& wi) const { return 1.0f / (1 + lambda(wo) + lambda(wi)); }

  /// Density of the visible normal h seen from wo (wo.z > 0): G1(wo) max(0, wo.h) D(h) / wo.z.
  float visibleNormalPdf(const Vec3& wo, const Vec3& h) const {
    const float c = dot(wo, h);
    if (c <= 0 || wo.z <= 0) return 0;
    return g1(wo) * c * d(h) / wo.z;
  }

  /// Draws a normal visible from wo (wo.z > 0) with density visibleNormalPdf (Heitz 2018,
  /// "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)): the view stretched to
  /// the unit-roughness configuration, a point on the projected hemisphere, unstretched.
  Vec3 sampleVisibleNormal(const Vec3& wo, Sample2 u) const {
    const Vec3 vh = normalize(Vec3(ax * wo.x, ay * wo.y, wo.z));
    const float len2 = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = len2 > 0 ? Vec3(-vh.y, vh.x, 0) * (1.0f / std::sqrt(len2)) : Vec3(1, 0, 0);
    const Vec3 t2 = cross(vh, t1);
    const float r = std::sqrt(u.u);
    const float phi = 2 * static_cast<float>(kPi) * u.v;
    const float p1 = r * std::cos(phi);
    const float s = 0.5f * (1 + vh.z);
    const float p2 = (1 - s) * std::sqrt(std::max(0.0f, 1 - p1 * p1)) + s * r * std::sin(phi);
    const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0f, 1 - p1 * p1 - p2 * p2));
    return normalize(Vec3(ax * nh.x, ay * nh.y, std::max(1e-7f, nh.z)));
  }
};

} // namespace nx
