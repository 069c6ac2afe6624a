#pragma once
// Direction sampling routines and their densities (all tested by chi-square against the pdf):
// shared by the integrators and the primitives that sample the directions they subtend.

#include <algorithm>
#include <cmath>

#include "core/concentric_disk.h"
#include "core/math_util.h"
#include "core/sampler.h"
#include "core/vec3.h"

namespace nx {

/// Cosine-weighted direction on the hemisphere around +z (Malley's method: a uniform point
/// of the concentric disk lifted to the hemisphere). Density cos(theta) / pi.
inline Vec3 sampleCosineHemisphere(Sample2 u) {
  float x = 0, y = 0;
  sampleConcentricDisk(u, x, y);
  return {x, y, std::sqrt(std::max(0.0f, 1 - x * x - y * y))};
}

/// Density of sampleCosineHemisphere for a direction with the given cos(theta).
inline float cosineHemispherePdf(float cosTheta) {
  return cosTheta > 0 ? cosTheta * static_cast<float>(kInvPi) : 0.0f;
}

/// 1 - cos(theta) from s = sin^2(theta) for theta <= pi/2, accurate to 1e-11 (relative) down
/// to cones of 1e-20 sr (a tiny light far away): 1 - sqrt(1 - s) loses digits to cancellation
/// for small s, where the series s/2 + s^2/8 + s^3/16 is used instead (relative remainder
/// 5 s^3 / 64 < 1e-13 for s < 1e-4). No division: this sits on the light sampler's critical path.
inline double oneMinusCosFromSin2(double sin2) {
  if (sin2 < 1e-4) return sin2 * (0.5 + sin2 * (0.125 + sin2 * 0.0625));
  return 1.0 - std::sqrt(std::max(0.0, 1.0 - sin2));
}

/// Uniform direction in the cone of half-angle theta_max around +z, given
/// oneMinusCosMax = 1 - cos(theta_max). Density 1 / (2 pi oneMinusCosMax). The sampled
/// 1 - cos(theta) is u.u * oneMinusCosMax, computed in double precision so that very narrow
/// cones stay accurate; the azimuth in single precision.
inline Vec3 sampleUniformCone(Sample2 u, double oneMinusCosMax) {
  const double oneMinusCos = u.u * oneMinusCosMax;
  const float sinTheta = static_cast<float>(std::sqrt(oneMinusCos * (2.0 - oneMinusCos)));
  const float phi = 2 * static_cast<float>(kPi) * u.v;
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi),
          static_cast<float>(1.0 - oneMinusCos)};
}

/// Density of sampleUniformCone.
inline double uniformConePdf(double oneMinusCosMax) {
  return 1.0 / (2 * kPi * oneMinusCosMax);
}

/// Uniform direction on the unit sphere. Density 1 / (4 pi).
inline Vec3 sampleUniformSphere(Sample2 u) {
  const float z = 1 - 2 * u.u;
  const float r = std::sqrt(std::max(0.0f, 1 - z * z));
  const float phi = 2 * static_cast<float>(kPi) * u.v;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

} // namespace nx
