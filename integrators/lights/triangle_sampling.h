#pragma once
// Uniform points on a triangle, for area lights.

#include <cmath>

#include "accel/shapes.h"
#include "core/sampler.h"

namespace nx {

/// Barycentrics (b0, b1, b2) of a uniform point on a triangle from u in [0, 1)^2 (the
/// square-root warp, Shirley 1990; area density 1 / A). Returned as b1, b2; b0 = 1 - b1 - b2.
inline void sampleUniformTriangle(Sample2 u, double& b1, double& b2) {
  const double su = std::sqrt(static_cast<double>(u.u));
  b1 = 1.0 - su;
  b2 = static_cast<double>(u.v) * su;
}

/// The point with barycentrics (1 - b1 - b2, b1, b2), in double precision.
inline Vec3d trianglePoint(const TriangleShape& t, double b1, double b2) {
  return t.a * (1.0 - b1 - b2) + t.b * b1 + t.c * b2;
}

} // namespace nx
