#pragma once
// Wavelength shifting at a diffuse fluorescent vertex, per lane (camera to light).

#include <cmath>

#include "core/sampler.h"
#include "integrators/render_scene.h"
#include "spectra/sampled_wavelengths.h"

namespace nx {

/// The excitation wavelengths chosen for the diffuse lobe at a fluorescent vertex and the
/// lobe's albedo per lane (D(o) + c(o), replacing rho). Each lane keeps its direction, which
/// all lanes share; only its current wavelength changes (fluorescence model, "Sampling it
/// in a hero-wavelength path tracer").
struct FluorescentShift {
  SampledWavelengths excited; ///< current wavelengths after the re-radiation choice
  SampledSpectrum albedo;     ///< D(o) + c(o) per lane
};

/// Draws the re-radiation choice of every lane (two sample values per lane).
inline FluorescentShift sampleFluorescentShift(const ReradiationMatrix& matrix,
                                               const SampledWavelengths& current,
                                               const SampledSpectrum& rho, PixelSampleStream& rng) {
  FluorescentShift s{current, SampledSpectrum::filled(1.0f)};
  for (int i = 0; i < kLanes; ++i) {
    const Sample2 u = rng.next2D();
    s.excited.lambda[i] = static_cast<float>(
        matrix.sampleExcitation(current.lambda[i], rho[i], u.u, u.v, s.albedo[i]));
  }
  return s;
}

} // namespace nx
