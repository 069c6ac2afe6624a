#pragma once
// Importance sampling of wavelengths over a range, with hero-wavelength rotation.

#include <array>

#include "spectra/sampled_wavelengths.h"

namespace nx {

/// Draws the wavelengths of a path from the "visible" density p(l) ~ 1/cosh^2(k (l - 538 nm)),
/// k = 0.0072/nm (the density pbrt-v4 and Mitsuba use, close to the CIE luminous response),
/// restricted and renormalised to [minNm, maxNm], as a table: the range is cut at the
/// wavelengths of the CDF values j / kSegments, and within each of those equal-probability
/// segments the density is uniform. Sampling is then a lookup and one interpolation per lane
/// (no logarithm), and pdf() is exactly the density sampled from (piecewise constant: the
/// smooth density's average over each segment). The hero wavelength comes from u; the others from u
/// + i/kLanes (mod 1) in primary sample space (Wilkie et al., "Hero Wavelength Spectral Sampling",
/// EGSR 2014), so every lane has the same marginal density p.
class WavelengthSampler {
public:
  /// Equal-probability segments of the tabulated density.
  static constexpr int kSegments = 2048;

  /// A sampler over [minNm, maxNm] (200 nm <= minNm < maxNm <= 1100 nm; bands lie in 300-1000).
  WavelengthSampler(double minNm, double maxNm);

  /// The kLanes wavelengths for primary sample u in [0, 1), with their pdfs.
  SampledWavelengths sample(float u) const;

  /// Wavelength for primary sample u (the inverse CDF).
  double wavelength(double u) const;
  /// Density at nm (0 outside the range).
  double pdf(double nm) const;

  /// Estimator weight of lane i: 1 / (kLanes * pdf_i), or 0 where pdf_i is 0. Summing
  /// f(lambda_i) * weight_i over the lanes estimates the integral of f over the range.
  static float laneWeight(const SampledWavelengths& w, int i) {
    return w.pdf[i] > 0 ? 1.0f / (static_cast<float>(kLanes) * w.pdf[i]) : 0.0f;
  }

  double minNm() const { return min_; }
  double maxNm() const { return max_; }

private:
  double min_, max_;
  std::array<double, kSegments + 1> knotNm_; ///< wavelength where the CDF is j / kSegments
  std::array<float, kSegments> segmentPdf_;  ///< density within segment j
};

} // namespace nx
