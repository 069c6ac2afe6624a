#pragma once
// Rays with a parametric validity interval.

#include <limits>

#include "core/vec3.h"

namespace nx {

/// A ray o + t d, valid for t in (tMin, tMax).
struct Ray {
  Vec3 o;
  Vec3 d;
  float tMin = 0.0f;
  float tMax = std::numeric_limits<float>::infinity();

  /// The point at parameter t.
  Vec3 at(float t) const { return o + d * t; }
};

} // namespace nx
