#pragma once
// Importance sampling of wavelengths over a range, with hero-wavelength rotation.

#include "spectra/sampled_wavelengths.h"

namespace nx {

/// Draws the wavelengths of a path from the "visible" density p(l) ~ 1/cosh^2(k (l - 538 nm)),
/// k = 0.0072/nm (the density pbrt-v4 and Mitsuba use, close to the CIE luminous response),
/// restricted and renormalised to [minNm, maxNm]. The hero wavelength comes from u; the
/// others from u + i/kLanes (mod 1) in primary sample space (Wilkie et al., "Hero Wavelength
/// Spectral Sampling", EGSR 2014), so every lane has the same marginal density p.
class WavelengthSampler {
public:
  /// A sampler over [minNm, maxNm] (200 nm <= minNm < maxNm <= 1100 nm; bands lie in 300-1000).
  WavelengthSampler(double minNm, double maxNm);

  /// The kLanes wavelengths for primary sample u in [0, 1), with their pdfs.
  SampledWavelengths sample(float u) const;

  /// Wavelength for primary sample u (the inverse CDF).
  double wavelength(double u) const;
  /// Density at nm (0 outside the range).
  double pdf(double nm) const;

  /// Estimator weight of lane i: 1 / (kLanes * pdf_i), or 0 for a terminated lane. Summing
  /// f(lambda_i) * weight_i over the lanes estimates the integral of f over the range.
  static float laneWeight(const SampledWavelengths& w, int i) {
    return w.pdf[i] > 0 ? 1.0f / (static_cast<float>(kLanes) * w.pdf[i]) : 0.0f;
  }

  double minNm() const { return min_; }
  double maxNm() const { return max_; }

private:
  double min_, max_;
  double tanhMin_, tanhRange_;
};

} // namespace nx
