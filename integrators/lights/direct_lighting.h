#pragma once
// The one next-event estimate every integrator uses: a light sample, its shadow ray, its
// weight.

#include "integrators/integrator.h"
#include "integrators/lights/light_sample.h"
#include "integrators/sampling.h"

namespace nx {

/// What a light sample contributes at a surface hit reached along rayDir: f(wi) Le w / pdf,
/// zero when the light is blocked or lies on the hit's own surface. `f(wi)` gives the BSDF
/// times |cos| per lane; with `mis`, w is the power heuristic against `bsdfPdf(wi)` (1 for
/// point lights), else 1. One shadow ray, spawned to the light's point with error-bounded
/// offsets at both ends.
template <class Eval, class BsdfPdf>
SampledSpectrum directLight(const RenderScene& scene, const SurfaceHit& hit, const Vec3& rayDir,
                            const LightSample& ls, Eval&& f, BsdfPdf&& bsdfPdf, bool mis,
                            TraceCounters& counters) {
  if (lightsItsOwnSurface(hit, ls, rayDir)) return {};
  const SampledSpectrum fv = f(ls.wi);
  if (fv.isBlack()) return {};
  ++counters.rays;
  if (scene.geometry->occluded(shadowRayTo(hit.p, hit.pError, hit.ng, ls))) return {};
  const float w = (ls.delta || !mis) ? 1.0f : powerHeuristic(ls.pdf, bsdfPdf(ls.wi));
  return fv * ls.radiance * (w / ls.pdf);
}

/// Direct light at a point p through media (offset by pError along ng; zero vectors for a point
/// in a medium, whose f and pdf are the phase function's): f T Le w / p_light, w the power
/// heuristic against pdf unless the light is a delta or `mis` is off.
template <class Eval, class Pdf, class Visible>
SampledSpectrum directLightAt(const Vec3& p, const Vec3& pError, const Vec3& ng,
                              const LightSample& ls, Eval&& f, Pdf&& pdf, bool mis,
                              Visible&& visible) {
  const SampledSpectrum fv = f(ls.wi);
  if (fv.isBlack()) return {};
  const SampledSpectrum T = visible(shadowRayTo(p, pError, ng, ls));
  if (T.isBlack()) return {};
  const float w = (ls.delta || !mis) ? 1.0f : powerHeuristic(ls.pdf, pdf(ls.wi));
  return fv * T * ls.radiance * (w / ls.pdf);
}

/// directLight through media, at a surface hit (a light never lights its own surface):
/// `visible(shadowRay)` gives the transmittance per lane (0 where blocked), e.g.
/// shadowTransmittance with the path's media (which counts its rays).
template <class Eval, class BsdfPdf, class Visible>
SampledSpectrum directLightThrough(const SurfaceHit& hit, const Vec3& rayDir, const LightSample& ls,
                                   Eval&& f, BsdfPdf&& bsdfPdf, bool mis, Visible&& visible) {
  if (lightsItsOwnSurface(hit, ls, rayDir)) return {};
  return directLightAt(hit.p, hit.pError, hit.ng, ls, f, bsdfPdf, mis, visible);
}

} // namespace nx
