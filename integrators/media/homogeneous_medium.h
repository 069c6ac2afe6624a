#pragma once
// A homogeneous participating medium: absorption and scattering coefficients (spectra, per
// scene unit of length), a Henyey-Greenstein lobe, and optionally a fluorescent dye, the same
// everywhere inside its shape.

#include <memory>
#include <optional>

#include "spectra/reradiation_matrix.h"
#include "spectra/sampled_wavelengths.h"
#include "spectra/spectrum.h"

namespace nx {

/// The medium filling a closed shape.
///
/// A dye (fluorescence model, docs/media.md) absorbs sigma_f(l) = peak a(l) (a: the model's
/// absorption curve with peak 1, per 5 nm bin of the re-radiation matrix) on top of sigma_a,
/// and re-emits isotropically: light at emission wavelength l_o arises per unit length from
/// the fluence at every excitation bin i as peak M[i][o] / (4 pi), with M the model's matrix
/// for a peak absorptance of 1 (M[i][o] = a_i Q e_o l_i / l_o). Its "in-scattering"
/// coefficient at l_o is thus sigma_fl(l_o) = peak c(o), c the matrix's column sum.
struct HomogeneousMedium {
  Spectrum sigmaA;                              ///< absorption coefficient (other than the dye's)
  Spectrum sigmaS;                              ///< scattering coefficient
  float g = 0;                                  ///< Henyey-Greenstein mean cosine
  std::shared_ptr<const ReradiationMatrix> dye; ///< the dye's matrix (peak absorptance 1), or null
  float dyePeak = 0; ///< the dye's peak absorption coefficient per unit length
  /// Emitted radiance Le: the medium is a source sigma_a Le per unit length and solid angle
  /// (Kirchhoff: deep inside, the radiance tends to Le), or null
  std::optional<Spectrum> emission;

  /// The emission source sigma_a Le of the lanes (sigma_a without the dye's absorption).
  SampledSpectrum emissionSource(const SampledWavelengths& lambda) const {
    SampledSpectrum a, le;
    sigmaA.evaluate(lambda, a);
    emission->evaluate(lambda, le);
    return a * le;
  }

  /// The lanes' coefficients: sigma_a + sigma_f (all absorption), sigma_s, and the dye's
  /// in-scattering sigma_fl (zero without a dye).
  void coefficients(const SampledWavelengths& lambda, SampledSpectrum& absorption,
                    SampledSpectrum& scattering, SampledSpectrum& fluorescent) const {
    sigmaA.evaluate(lambda, absorption);
    sigmaS.evaluate(lambda, scattering);
    fluorescent = SampledSpectrum();
    if (!dye) return;
    for (int i = 0; i < kLanes; ++i) {
      const int bin = ReradiationMatrix::binOf(lambda.lambda[i]);
      if (bin < 0) continue;
      absorption[i] += dyePeak * static_cast<float>(dye->absorptance(bin));
      fluorescent[i] = dyePeak * static_cast<float>(dye->columnSum(bin));
    }
  }
};

} // namespace nx
