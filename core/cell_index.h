#pragma once
// Float-to-index conversions defined for every input: a sample value or a direction turned into
// a table index. A cast of NaN, or of a value beyond the integer's range, is undefined behaviour
// (CI's sanitizer pass builds with -fsanitize=float-cast-overflow to find the casts left).

#include <algorithm>

namespace nx {

/// The unit-width cell that x falls in among cells 0..n-1 (n >= 1): floor(x) clamped to
/// [0, n - 1]; NaN gives 0.
template <class F>
inline int cellIndex(F x, int n) {
  if (!(x > F(0))) return 0; // also NaN
  if (!(x < static_cast<F>(n - 1))) return n - 1;
  return std::min(static_cast<int>(x), n - 1);
}

} // namespace nx
