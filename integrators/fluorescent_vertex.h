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

/// x + shift modulo 1, for x in [0, 1) and shift in [0, 1).
inline float rotateUnit(float x, float shift) {
  const float r = x + shift;
  return r >= 1.0f ? r - 1.0f : r;
}

/// Draws the re-radiation choice of every lane from one 2D sample: lane i uses it rotated by
/// (i / kLanes, frac(i phi)) (a Cranley-Patterson rotation), so each lane's sample is
/// uniform on its own (the estimate of every lane is unbiased) while the lanes' choices are
/// stratified among themselves, like the hero wavelengths.
/// `concentration`: the dye's relative concentration at the vertex (a concentration map), or
/// null for the matrix as it is.
inline FluorescentShift sampleFluorescentShift(const ReradiationMatrix& matrix,
                                               const SampledWavelengths& current,
                                               const SampledSpectrum& rho, PixelSampleStream& rng,
                                               const float* concentration = nullptr) {
  FluorescentShift s{current, SampledSpectrum::filled(1.0f)};
  const Sample2 u = rng.next2D();
  constexpr float kGoldenFraction = 0.6180339887f;
  for (int i = 0; i < kLanes; ++i) {
    const float shiftV = static_cast<float>(i) * kGoldenFraction;
    const float ui = rotateUnit(u.u, static_cast<float>(i) / static_cast<float>(kLanes));
    const float vi = rotateUnit(u.v, shiftV - std::floor(shiftV));
    s.excited.lambda[i] =
        concentration ? matrix.sampleExcitationScaled(current.lambda[i], rho[i], *concentration, ui,
                                                      vi, s.albedo[i])
                      : matrix.sampleExcitation(current.lambda[i], rho[i], ui, vi, s.albedo[i]);
  }
  return s;
}

} // namespace nx
