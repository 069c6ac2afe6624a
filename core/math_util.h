#pragma once
// Scalar constants and small helpers shared by every module.

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace nx {

/// Pi in double precision.
inline constexpr double kPi = 3.14159265358979323846;
/// 1 / pi in double precision.
inline constexpr double kInvPi = 0.31830988618379067154;

/// Linear interpolation between a (t = 0) and b (t = 1).
template <typename T>
constexpr T lerp(T a, T b, T t) {
  return a + (b - a) * t;
}

/// x squared.
template <typename T>
constexpr T sqr(T x) {
  return x * x;
}

/// Largest float strictly below 1, the upper end of every [0, 1) sample.
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

/// Maps 32 random bits to a float uniformly in [0, 1).
inline float bitsToUnitFloat(uint32_t bits) {
  return std::min(static_cast<float>(bits >> 8) * 0x1p-24f, kOneMinusEpsilon);
}

} // namespace nx
