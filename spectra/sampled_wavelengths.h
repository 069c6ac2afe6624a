#pragma once
// The wavelengths one path carries (hero + rotated secondaries) and values at them.

#include <array>
#include <cstddef>

#ifndef NX_LANES
#define NX_LANES 8
#endif

namespace nx {

/// Number of wavelengths traced together by one path (a compile-time constant).
inline constexpr int kLanes = NX_LANES;
static_assert(kLanes >= 1 && kLanes <= 64, "NX_LANES must be in 1..64");

/// Values of a spectral quantity at the kLanes wavelengths of a path.
struct SampledSpectrum {
  std::array<float, kLanes> v{};

  /// Lane i.
  float& operator[](std::size_t i) { return v[i]; }
  /// Lane i.
  float operator[](std::size_t i) const { return v[i]; }
  /// Largest lane value.
  float maxValue() const {
    float m = v[0];
    for (float x : v) m = x > m ? x : m;
    return m;
  }
  /// True if every lane is zero.
  bool isBlack() const {
    for (float x : v)
      if (x != 0) return false;
    return true;
  }
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

/// The estimator of the hero lane alone: every secondary lane zeroed, the hero scaled by
/// kLanes, so that with the film's fixed lane weight 1 / (kLanes pdf) it weighs 1 / pdf.
/// Applied to a path's throughput when its direction starts to depend on the hero wavelength
/// (a dispersive refraction): contributions gathered before keep every lane and their weights.
inline SampledSpectrum heroOnly(SampledSpectrum s) {
  for (int i = 1; i < kLanes; ++i) s[i] = 0;
  s[0] *= static_cast<float>(kLanes);
  return s;
}

/// The wavelengths of one path and the pdf each was drawn with (marginal, per lane).
struct SampledWavelengths {
  std::array<float, kLanes> lambda{}; ///< nm
  std::array<float, kLanes> pdf{};    ///< 1/nm

  /// Number of lanes.
  static constexpr std::size_t size() { return kLanes; }
  /// Wavelength of lane i (so a spectrum can be evaluated over all lanes at once).
  float operator[](std::size_t i) const { return lambda[i]; }
};

} // namespace nx
