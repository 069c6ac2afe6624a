#pragma once
// The wavelengths one path carries (hero + rotated secondaries) and values at them.

#include <array>
#include <cstddef>

#ifndef NX_LANES
#define NX_LANES 4
#endif

namespace nx {

/// Number of wavelengths traced together by one path (a compile-time constant).
inline constexpr int kLanes = NX_LANES;
static_assert(kLanes >= 1 && kLanes <= 64, "NX_LANES must be in 1..64");

/// Values of a spectral quantity at the kLanes wavelengths of a path.
struct SampledSpectrum {
  std::array<float, kLanes> v{};

  /// Lane i.
  float& operator[](int i) { return v[static_cast<std::size_t>(i)]; }
  /// Lane i.
  float operator[](int i) const { return v[static_cast<std::size_t>(i)]; }
  /// Number of lanes (for generic code evaluating spectra lane by lane).
  static constexpr std::size_t size() { return kLanes; }

  /// Every lane set to x.
  static SampledSpectrum filled(float x) {
    SampledSpectrum s;
    s.v.fill(x);
    return s;
  }
  SampledSpectrum& operator*=(const SampledSpectrum& o) {
    for (int i = 0; i < kLanes; ++i) v[i] *= o.v[i];
    return *this;
  }
  SampledSpectrum& operator+=(const SampledSpectrum& o) {
    for (int i = 0; i < kLanes; ++i) v[i] += o.v[i];
    return *this;
  }
  SampledSpectrum& operator*=(float s) {
    for (auto& x : v) x *= s;
    return *this;
  }
};

inline SampledSpectrum operator*(SampledSpectrum a, const SampledSpectrum& b) {
  return a *= b;
}
inline SampledSpectrum operator+(SampledSpectrum a, const SampledSpectrum& b) {
  return a += b;
}
inline SampledSpectrum operator*(SampledSpectrum a, float s) {
  return a *= s;
}

/// The wavelengths of one path and the pdf each was drawn with (marginal, per lane).
struct SampledWavelengths {
  std::array<float, kLanes> lambda{}; ///< nm
  std::array<float, kLanes> pdf{};    ///< 1/nm; 0 marks a terminated secondary lane

  /// Number of lanes.
  static constexpr std::size_t size() { return kLanes; }
  /// Wavelength of lane i (so a spectrum can be evaluated over all lanes at once).
  float operator[](std::size_t i) const { return lambda[i]; }
};

} // namespace nx
