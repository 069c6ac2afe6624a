#pragma once
// The Henyey-Greenstein phase function (Henyey & Greenstein 1941): the scattering lobe of a
// participating medium, one parameter g = mean cosine of the scattering angle (g > 0 forward,
// g < 0 backward, 0 isotropic). Directions are directions of travel: cos(theta) is the dot
// product of the direction before scattering and the direction after.

#include <algorithm>
#include <cmath>

#include "core/frame.h"
#include "core/math_util.h"
#include "core/sampler.h"
#include "core/vec3.h"

namespace nx {

/// p(cos theta) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos theta)^(3/2)), per steradian.
inline float henyeyGreenstein(float cosTheta, float g) {
  const float denom = 1 + g * g - 2 * g * cosTheta;
  return (1 - g * g) / (4 * static_cast<float>(kPi) * denom * std::sqrt(std::max(denom, 1e-12f)));
}

/// Draws a direction after scattering from `dIn` (unit) with density henyeyGreenstein: the
/// inverse of the lobe's CDF in cos theta (exact; the isotropic limit for |g| < 1e-3).
inline Vec3 sampleHenyeyGreenstein(const Vec3& dIn, float g, Sample2 u) {
  float cosTheta;
  if (std::abs(g) < 1e-3f) {
    cosTheta = 1 - 2 * u.u;
  } else {
    const float s = (1 - g * g) / (1 - g + 2 * g * u.u);
    cosTheta = (1 + g * g - s * s) / (2 * g);
  }
  cosTheta = std::clamp(cosTheta, -1.0f, 1.0f);
  const float sinTheta = std::sqrt(std::max(0.0f, 1 - cosTheta * cosTheta));
  const float phi = 2 * static_cast<float>(kPi) * u.v;
  const Frame f = Frame::fromNormal(dIn);
  return normalize(f.s * (sinTheta * std::cos(phi)) + f.t * (sinTheta * std::sin(phi)) +
                   f.n * cosTheta);
}

} // namespace nx
