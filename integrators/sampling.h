#pragma once
// Direction sampling routines (core/direction_sampling.h) and the weights of multiple
// importance sampling.

#include <cmath>

#include "core/direction_sampling.h"

namespace nx {

/// The power heuristic with exponent 2 for one sample from each of two strategies
/// (Veach 1997): weight of the strategy with density a. Written as 1 / (1 + (b/a)^2) so that
/// densities beyond 1e19 (a small light seen from 1e11 away has a cone pdf of 1e22) do not
/// overflow a^2 into inf / inf.
inline float powerHeuristic(float a, float b) {
  if (std::isinf(a)) return 1.0f;
  if (!(a > 0)) return 0.0f;
  const float r = b / a; // may be inf (then the weight is 0)
  return 1.0f / (1.0f + r * r);
}

} // namespace nx
