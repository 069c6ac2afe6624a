#pragma once
// A homogeneous participating medium: absorption and scattering coefficients (spectra, per
// scene unit of length) and a Henyey-Greenstein lobe, the same everywhere inside its shape.

#include "spectra/sampled_wavelengths.h"
#include "spectra/spectrum.h"

namespace nx {

/// The medium filling a closed shape.
struct HomogeneousMedium {
  Spectrum sigmaA; ///< absorption coefficient
  Spectrum sigmaS; ///< scattering coefficient
  float g = 0;     ///< Henyey-Greenstein mean cosine

  /// sigma_a and sigma_s at the lanes' wavelengths.
  void coefficients(const SampledWavelengths& lambda, SampledSpectrum& a,
                    SampledSpectrum& s) const {
    sigmaA.evaluate(lambda, a);
    sigmaS.evaluate(lambda, s);
  }
};

} // namespace nx
