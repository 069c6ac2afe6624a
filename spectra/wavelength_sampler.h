#pragma once
// Importance sampling of wavelengths over a range, with hero-wavelength rotation.

#include <array>
#include <functional>

#include "spectra/sampled_wavelengths.h"
#include "spectra/sensor.h"

namespace nx {

/// Draws the wavelengths of a path from a density over [minNm, maxNm], as a table: the range is
/// cut at the wavelengths of the CDF values j / kSegments, and within each of those
/// equal-probability segments the density is uniform. Sampling is then a lookup and one
/// interpolation per lane, and pdf() is exactly the density sampled from (piecewise constant:
/// the given density's average over each segment). The hero wavelength comes from u; the others
/// from u + i/kLanes (mod 1) in primary sample space (Wilkie et al., "Hero Wavelength Spectral
/// Sampling", EGSR 2014), so every lane has the same marginal density p and the lanes of one
/// path are stratified over the density's mass.
/// The densities: the "visible" p(l) ~ 1/cosh^2(k (l - 538 nm)), k = 0.0072/nm (close to the
/// CIE luminous response; pbrt-v4 and Mitsuba use it), and the sensor density (forSensor).
class WavelengthSampler {
public:
  /// Equal-probability segments of the tabulated density.
  static constexpr int kSegments = 2048;

  /// The visible density over [minNm, maxNm] (200 nm <= minNm < maxNm <= 1100 nm).
  WavelengthSampler(double minNm, double maxNm);
  /// A density given as a function over [minNm, maxNm] (not necessarily normalised; its
  /// integral must be positive), integrated on a grid of at most `gridNm` spacing.
  WavelengthSampler(double minNm, double maxNm, const std::function<double(double)>& density,
                    double gridNm);
  /// The density that serves a sensor and the colour channels: half the lanes from the mixture
  /// of the sensor's normalised responses (each band the same share), half from the visible
  /// density over 360-830 nm (XYZ, the preview), over [minNm, maxNm] (the traced range).
  static WavelengthSampler forSensor(const Sensor& sensor, double minNm, double maxNm);
  /// The visible density's value (unnormalised) at nm.
  static double visibleShape(double nm);

  /// The kLanes wavelengths for primary sample u in [0, 1), with their pdfs: lane i at
  /// u + i / kLanes (mod 1). The same as sample(frac(kLanes u), floor(kLanes u) / kLanes).
  SampledWavelengths sample(float u) const;
  /// The kLanes wavelengths for two primary samples: every lane at the same offset `offset`
  /// within its own stratum [j / kLanes, (j + 1) / kLanes) of primary sample space, the hero
  /// (lane 0) in stratum h = floor(kLanes heroStratum), lane i in stratum (h + i) mod kLanes.
  /// The lanes of all samples of a pixel are as stratified as the offsets are: with offsets
  /// from a stratified sequence (one per stratum of 1 / n over n samples) the n kLanes
  /// wavelengths fall one per stratum of 1 / (n kLanes), whereas sample(u) stratifies only
  /// frac(kLanes u), digits of u a short sequence leaves random. The hero is uniform when
  /// heroStratum is uniform and independent of offset.
  SampledWavelengths sample(float offset, float heroStratum) const;

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
  void build(const std::function<double(double)>& density, double gridNm);
  double min_, max_;
  std::array<double, kSegments + 1> knotNm_; ///< wavelength where the CDF is j / kSegments
  std::array<float, kSegments> segmentPdf_;  ///< density within segment j
};

} // namespace nx
