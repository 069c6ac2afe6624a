#pragma once
// Free-flight sampling in a homogeneous medium for all lanes of a hero-wavelength path.
//
// The distance is drawn from the hero lane's in-scattering coefficient sigma_in = sigma_s +
// sigma_fl (elastic scattering and a dye's re-emission), sigma_in exp(-sigma_in t), and
// absorption is a weight: the radiance along a segment towards a surface at tSurface is
// T(tSurface) L_surface + integral_0^tSurface T(t) (sigma_s L_s + sigma_fl L_fl)(t) dt with
// T(t) = exp(-sigma_t t), so drawing t with the in-scattering rate alone leaves bounded
// weights exp(-(sigma_t - sigma_in) t) (a pure absorber attenuates exactly; no path is lost
// to a sampled absorption). The event is then elastic with the hero's probability
// sigma_s / sigma_in, else a re-emission.
//
// Chromatic media make the lanes' densities differ, so the lanes are combined by spectral MIS
// over whole paths (Wilkie et al. 2014, "Hero Wavelength Spectral Sampling"; Miller, Georgiev
// & Jarosz 2019, sec. 5.2; pbrt-v4's "rescaled path probabilities"): the path keeps
// beta_i = f_i / p_hero and r_j = p_j / p_hero (products over its events), and a contribution
// of lane i is beta_i Le_i / ((1/n) sum_j r_j): the balance heuristic over the n lanes as
// techniques, the hero being a uniformly chosen lane of the rotated set. (Balancing each event
// separately, with one hero for the whole path, is biased: a furnace read 1.2 to 600.) Once the
// secondary lanes are terminated (dispersion), the hero's own density alone counts.
//
// An emitting medium (source sigma_a Le per unit length and solid angle) adds, per flight, the
// track-length estimate of the emission along the segment the flight covers, [0, t_end]:
// a point at s is covered with the hero's probability exp(-sigma_in s), so lane i gets
// integral_0^t_end exp(-(sigma_t,i - sigma_in) s) ds sigma_a,i Le_i, unbiased for any hero,
// weighted by the path before the flight (its beta and spectral MIS divisor).

#include <cmath>
#include <cstdint>

#include "integrators/media/homogeneous_medium.h"

namespace nx {

/// What ends a flight through a medium.
enum class MediumEvent : uint8_t {
  None,      ///< nothing before the surface
  Scatter,   ///< elastic scattering (Henyey-Greenstein)
  Fluoresce, ///< absorption by the dye and isotropic re-emission at a longer wavelength
};

/// Where a path's flight through a medium ends.
struct FreeFlight {
  MediumEvent event = MediumEvent::None;
  float t = 0; ///< the event's distance along the (unit) direction
};

/// integral_0^t exp(-c s) ds for a rate c of any sign (t may be infinite when c > 0).
inline float decayIntegral(float c, float t) {
  if (std::isinf(t)) return c > 0 ? 1.0f / c : 0.0f; // c <= 0 over an endless flight: no source
  const float x = c * t;
  return std::abs(x) < 1e-4f ? t * (1 - 0.5f * x) : -std::expm1(-x) / c;
}

/// Draws the flight from a point towards a surface at distance tSurface (infinity: none) with
/// 1D samples u (distance) and uEvent (kind); multiplies `beta` by f_i / p_hero and `ratios` by
/// p_j / p_hero (see above). For an emitting medium, `glow` (if given) receives the emission
/// collected along the flight per unit of the path's weight before it.
inline FreeFlight sampleFreeFlight(const HomogeneousMedium& medium,
                                   const SampledWavelengths& lambda, float tSurface, float u,
                                   float uEvent, SampledSpectrum& beta, SampledSpectrum& ratios,
                                   SampledSpectrum* glow = nullptr) {
  SampledSpectrum sa, ss, sfl;
  medium.coefficients(lambda, sa, ss, sfl);
  const SampledSpectrum sin = ss + sfl;
  FreeFlight f;
  f.t = sin[0] > 0 ? -std::log1p(-u) / sin[0] : INFINITY;
  if (f.t < tSurface)
    f.event = uEvent * sin[0] < ss[0] ? MediumEvent::Scatter : MediumEvent::Fluoresce;
  const float t = f.event == MediumEvent::None ? tSurface : f.t;
  if (glow) {
    const SampledSpectrum source = medium.emissionSource(lambda);
    for (int i = 0; i < kLanes; ++i)
      (*glow)[i] = source[i] > 0 ? source[i] * decayIntegral(sa[i] + ss[i] - sin[0], t) : 0.0f;
  }
  // exp(-c t) for a coefficient c, with exp(-0 * inf) = 1
  auto decay = [t](float c) { return c > 0 ? (std::isinf(t) ? 0.0f : std::exp(-c * t)) : 1.0f; };
  SampledSpectrum p, fv;
  for (int i = 0; i < kLanes; ++i) {
    const float rate = f.event == MediumEvent::None      ? 1.0f
                       : f.event == MediumEvent::Scatter ? ss[i]
                                                         : sfl[i];
    p[i] = rate * decay(sin[i]);
    fv[i] = rate * decay(sa[i] + ss[i]);
  }
  if (!(p[0] > 0)) { // underflow far along a path: nothing left to estimate
    beta = SampledSpectrum();
    return f;
  }
  const float inv = 1.0f / p[0];
  beta *= fv * inv;
  ratios *= p * inv;
  return f;
}

/// The divisor of a contribution: the mean of the lanes' path-density ratios, or 1 for a path
/// carried by the hero alone.
inline float spectralMisDivisor(const SampledSpectrum& ratios, bool heroAlone) {
  if (heroAlone) return 1.0f;
  float sum = 0;
  for (int i = 0; i < kLanes; ++i) sum += ratios[i];
  return sum / static_cast<float>(kLanes);
}

} // namespace nx
