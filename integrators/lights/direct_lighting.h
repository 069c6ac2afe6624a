#pragma once
// The one next-event estimate every integrator uses: a light sample, its shadow ray, its
// weight.

#include "integrators/integrator.h"
#include "integrators/lights/light_sample.h"
#include "integrators/sampling.h"

namespace nx {

/// True when the sample lies on the surface it is meant to light, where it cannot be seen: the
/// same triangle, or a primitive whose light cannot reach itself there (a flat one anywhere, a
/// closed convex one from outside: rayDir arrives from outside). A point rounded just inside a
/// sphere would otherwise be lit by its own emission "from inside"; from the inside (a camera
/// in a furnace) a sphere does light itself.
inline bool lightsItsOwnSurface(const SurfaceHit& hit, const LightSample& ls, const Vec3& rayDir) {
  if (ls.delta || ls.infinite || ls.kind != hit.kind || ls.shape != hit.index) return false;
  if (!isAnalytic(hit.kind)) return ls.prim == hit.prim; // a triangle (planes are not sampled)
  switch (visitAnalyticKind(hit.kind, []<class P>() { return P::kSelfLighting; })) {
  case SelfLighting::Never:
    return true;
  case SelfLighting::FromInside:
    return dot(rayDir, hit.ng) < 0;
  case SelfLighting::Possible: // shadow rays tell
    return false;
  }
  return false; // not reached: every case returns (-Werror=switch)
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

/// directLightAt at a surface hit reached along rayDir (a light never lights its own surface):
/// `visible(shadowRay)` gives the transmittance per lane (0 where blocked), e.g.
/// shadowTransmittance with the path's media (which counts its rays).
template <class Eval, class BsdfPdf, class Visible>
SampledSpectrum directLightThrough(const SurfaceHit& hit, const Vec3& rayDir, const LightSample& ls,
                                   Eval&& f, BsdfPdf&& bsdfPdf, bool mis, Visible&& visible) {
  if (lightsItsOwnSurface(hit, ls, rayDir)) return {};
  return directLightAt(hit.p, hit.pError, hit.ng, ls, f, bsdfPdf, mis, visible);
}

/// directLightThrough in a scene without media: the shadow ray is blocked or not (and counted).
/// `f(wi)` gives the BSDF times |cos| per lane; with `mis`, the weight is the power heuristic
/// against `bsdfPdf(wi)` (1 for point lights).
template <class Eval, class BsdfPdf>
SampledSpectrum directLight(const RenderScene& scene, const SurfaceHit& hit, const Vec3& rayDir,
                            const LightSample& ls, Eval&& f, BsdfPdf&& bsdfPdf, bool mis,
                            TraceCounters& counters) {
  return directLightThrough(hit, rayDir, ls, f, bsdfPdf, mis, [&](const Ray& shadow) {
    ++counters.rays;
    return SampledSpectrum::filled(scene.geometry->occluded(shadow) ? 0.0f : 1.0f);
  });
}

} // namespace nx
