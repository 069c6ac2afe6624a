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

/// Lane i's share of a 2D sample shared by the lanes: u rotated by (i / kLanes, frac(i phi))
/// (a Cranley-Patterson rotation), so each lane's sample is uniform on its own while the
/// lanes' samples are stratified among themselves, like the hero wavelengths.
inline Sample2 laneSample(const Sample2& u, int i) {
  constexpr float kGoldenFraction = 0.6180339887f;
  const float shiftV = static_cast<float>(i) * kGoldenFraction;
  return {rotateUnit(u.u, static_cast<float>(i) / static_cast<float>(kLanes)),
          rotateUnit(u.v, shiftV - std::floor(shiftV))};
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
  for (int i = 0; i < kLanes; ++i) {
    const Sample2 ui = laneSample(u, i);
    s.excited.lambda[i] =
        concentration ? matrix.sampleExcitationScaled(current.lambda[i], rho[i], *concentration,
                                                      ui.u, ui.v, s.albedo[i])
                      : matrix.sampleExcitation(current.lambda[i], rho[i], ui.u, ui.v, s.albedo[i]);
  }
  return s;
}

/// Next-event estimation's excitation at a fluorescent vertex towards one light: per lane the
/// column's event (the vertex's shift) and one per guide of the light (its spectrum's, or one
/// per relighting target), with their MIS weights (ReradiationMatrix::guidedExcitations).
struct GuidedShift {
  SampledWavelengths guided[kMaxExcitationGuides];    ///< each guide's events' wavelengths
  SampledSpectrum columnWeight;                       ///< weight of the light at shift.excited
  SampledSpectrum guidedWeight[kMaxExcitationGuides]; ///< weight of the light at guided[t]
  int count = 0;                                      ///< guides
};

/// The guided events of every lane, guide t's from u[t] (stratified across lanes as the
/// shift's).
inline GuidedShift guideFluorescentShift(const ReradiationMatrix& matrix,
                                         const SampledWavelengths& current,
                                         const FluorescentShift& shift, const SampledSpectrum& rho,
                                         float concentration, const ExcitationGuides& guides,
                                         const Sample2* u) {
  GuidedShift g;
  g.count = guides.count;
  for (int t = 0; t < g.count; ++t) g.guided[t] = current;
  for (int i = 0; i < kLanes; ++i) {
    ReradiationMatrix::Sample2Pair uv[kMaxExcitationGuides];
    for (int t = 0; t < g.count; ++t) {
      const Sample2 ui = laneSample(u[t], i);
      uv[t] = {ui.u, ui.v};
    }
    GuidedExcitations e;
    matrix.guidedExcitations(current.lambda[i], shift.excited.lambda[i], rho[i], concentration,
                             guides, uv, e);
    g.columnWeight[i] = e.weight[0];
    for (int t = 0; t < g.count; ++t) {
      g.guided[t].lambda[i] = e.nm[t + 1];
      g.guidedWeight[t][i] = e.weight[t + 1];
    }
  }
  return g;
}

} // namespace nx
