#pragma once
// The concentric map from the unit square to the unit disk (shared by direction sampling and
// the primitives' area sampling).

#include <cmath>

#include "core/math_util.h"
#include "core/sampler.h"

namespace nx {

/// Uniform point on the unit disk (the concentric mapping of Shirley & Chiu 1997: it keeps
/// the square's stratification). Density 1 / pi.
inline void sampleConcentricDisk(Sample2 u, float& x, float& y) {
  const float a = 2 * u.u - 1, b = 2 * u.v - 1;
  float r = 0, phi = 0;
  if (a != 0 || b != 0) {
    constexpr float quarterPi = static_cast<float>(kPi / 4);
    if (std::abs(a) > std::abs(b)) {
      r = a;
      phi = quarterPi * (b / a);
    } else {
      r = b;
      phi = 2 * quarterPi - quarterPi * (a / b);
    }
  }
  x = r * std::cos(phi), y = r * std::sin(phi);
}

} // namespace nx
