#pragma once
// Direction sampling routines and their densities (all tested by chi-square against the pdf).

#include <algorithm>
#include <cmath>

#include "core/math_util.h"
#include "core/sampler.h"
#include "core/vec3.h"

namespace nx {

/// Cosine-weighted direction on the hemisphere around +z (Malley's method through the
/// concentric disk mapping of Shirley & Chiu 1997). Density cos(theta) / pi.
inline Vec3 sampleCosineHemisphere(Sample2 u) {
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
  const float x = r * std::cos(phi), y = r * std::sin(phi);
  return {x, y, std::sqrt(std::max(0.0f, 1 - x * x - y * y))};
}

/// Density of sampleCosineHemisphere for a direction with the given cos(theta).
inline float cosineHemispherePdf(float cosTheta) {
  return cosTheta > 0 ? cosTheta * static_cast<float>(kInvPi) : 0.0f;
}

/// Uniform direction in the cone of half-angle acos(cosMax) around +z. Density
/// 1 / (2 pi (1 - cosMax)). cos(theta) is interpolated in double precision so that very
/// narrow cones (a small light far away) stay accurate.
inline Vec3 sampleUniformCone(Sample2 u, double cosMax) {
  const double cosTheta = 1.0 - u.u * (1.0 - cosMax);
  const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  const double phi = 2 * kPi * u.v;
  return {static_cast<float>(sinTheta * std::cos(phi)),
          static_cast<float>(sinTheta * std::sin(phi)), static_cast<float>(cosTheta)};
}

/// Density of sampleUniformCone.
inline double uniformConePdf(double cosMax) {
  return 1.0 / (2 * kPi * (1.0 - cosMax));
}

/// Uniform direction on the unit sphere. Density 1 / (4 pi).
inline Vec3 sampleUniformSphere(Sample2 u) {
  const float z = 1 - 2 * u.u;
  const float r = std::sqrt(std::max(0.0f, 1 - z * z));
  const float phi = 2 * static_cast<float>(kPi) * u.v;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

/// The power heuristic with exponent 2 for one sample from each of two strategies
/// (Veach 1997): weight of the strategy with density a.
inline float powerHeuristic(float a, float b) {
  if (std::isinf(a)) return 1.0f;
  const float a2 = a * a, b2 = b * b;
  return a2 + b2 > 0 ? a2 / (a2 + b2) : 0.0f;
}

} // namespace nx
