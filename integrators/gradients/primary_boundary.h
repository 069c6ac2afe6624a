#pragma once
// The boundary term of primary visibility (docs/inverse.md, "Shape and camera"). A pixel's
// value is the integral of the radiance over its area; where a moving shape's outline crosses
// the pixel the integrand jumps, and the integral's derivative gains
//   integral over the outline of (L_in - L_out) v_n dl
// (Reynolds' transport theorem), v_n the outline's speed along its outward normal in the image.
// With the outline written implicitly as phi(y, theta) = 0 (phi < 0 where the shape is seen),
// v_n = -(d phi / d theta) / |grad_y phi|. The outline is sampled by its own parameter (edge
// sampling: Li, Aittala, Durand and Lehtinen 2018, "Differentiable Monte Carlo ray tracing
// through edge sampling"), L_in and L_out are path-traced just inside and just outside it with
// the same random numbers, and each sample lands in the pixel it falls in.

#include <cstdint>
#include <functional>
#include <vector>

#include "core/sampler.h"
#include "integrators/film.h"
#include "integrators/integrator.h"
#include "spectra/sampled_wavelengths.h"

namespace nx {

/// One sample of the boundary term for one slot: the pixel it falls in, its wavelengths and
/// replicate, and its share of the pixel's derivative per lane (the sample count divided out).
struct BoundaryContribution {
  int x = 0, y = 0;
  bool odd = false;
  uint32_t slot = 0;
  SampledWavelengths lambda;
  SampledSpectrum value;
};

/// What the boundary sampling needs of the render.
struct PrimaryBoundaryRequest {
  SamplerKind sampler = SamplerKind::SobolOwen;
  uint32_t seed = 0;
  int samplesPerPixel = 1; ///< about this many boundary samples per pixel of outline
  PixelRect rect;          ///< the pixels rendered
  /// Draws a sample's wavelengths from its random numbers (as the camera samples do).
  std::function<SampledWavelengths(PixelSampleStream&)> wavelengths;
};

/// The boundary term's samples for every moving outline, handed to `consume` one by one in a
/// fixed order (independent of the thread count): the moving spheres' silhouettes and meshes'
/// outline edges seen from the pinhole, their shadows' edges under point and spot lights, and
/// when the camera moves every sphere's silhouette and every plane's horizon; about
/// samplesPerPixel samples per pixel of each outline's length. Each sample traces two paths.
void primaryBoundary(const IntegratorContext& ctx, const PrimaryBoundaryRequest& request,
                     const std::function<void(const BoundaryContribution&)>& consume,
                     uint64_t& rays);

} // namespace nx
