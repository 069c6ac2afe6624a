#pragma once
// Index of refraction as a function of wavelength (constant or dispersive).

#include <array>
#include <cmath>
#include <optional>

namespace nx {

/// n(lambda): a constant, Cauchy's formula n = A + B / l^2 + C / l^4, or Sellmeier's
/// n^2 = 1 + sum B_i l^2 / (l^2 - C_i), with l in micrometres.
struct IorModel {
  enum class Kind { Constant, Cauchy, Sellmeier };
  Kind kind = Kind::Constant;
  std::array<double, 6> c{1.5, 0, 0, 0, 0, 0}; ///< n; or A, B, C; or B1, B2, B3, C1, C2, C3

  /// A wavelength-independent index.
  static IorModel constant(double n) { return {Kind::Constant, {n, 0, 0, 0, 0, 0}}; }

  /// True when n depends on wavelength (refracted directions then do too).
  bool dispersive() const { return kind != Kind::Constant; }

  /// n at wavelength nm.
  double at(double nm) const {
    const double l = nm * 1e-3, l2 = l * l;
    switch (kind) {
    case Kind::Constant:
      return c[0];
    case Kind::Cauchy:
      return c[0] + c[1] / l2 + c[2] / (l2 * l2);
    case Kind::Sellmeier:
      return std::sqrt(1.0 + c[0] * l2 / (l2 - c[3]) + c[1] * l2 / (l2 - c[4]) +
                       c[2] * l2 / (l2 - c[5]));
    }
    return c[0];
  }
};

/// Built-in glasses (Sellmeier coefficients): "bk7" (Schott N-BK7), "diamond" (n_D = 2.417),
/// "fused_silica" (Malitson 1965). Returns false for other names.
bool namedGlass(const char* name, IorModel& out);

/// A wavelength in [loNm, hiNm] where n is not finite or not within [nMin, nMax] (a
/// Sellmeier pole counts), or nullopt if n stays inside at every wavelength of the interval.
/// Exact, not sampled: Cauchy's n is a quadratic in 1/l^2 (ends and vertex checked);
/// Sellmeier's n^2 - 1 is a sum of terms B s / (s - C), s = l^2, each monotone between poles,
/// so interval bounds refined by bisection decide every sub-interval.
std::optional<double> iorOutsideRange(const IorModel& m, double loNm, double hiNm, double nMin,
                                      double nMax);

} // namespace nx
