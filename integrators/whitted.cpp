#include <cmath>

#include "core/ray_offset.h"
#include "integrators/fluorescent_vertex.h"
#include "integrators/integrator.h"
#include "integrators/materials/bsdf.h"
#include "integrators/materials/fresnel.h"

namespace nx {
namespace {

void whitted(const IntegratorContext& ctx, const Ray& ray, const SampledWavelengths& lambda,
             SampledSpectrum beta, int bounce, bool heroOnlyPath, PixelSampleStream& rng,
             TraceCounters& counters, SampledSpectrum& L) {
  const RenderScene& scene = *ctx.scene;
  SurfaceHit hit;
  ++counters.rays;
  if (!scene.geometry->intersect(ray, hit)) {
    if (scene.background) L += beta * evaluate(*scene.background, lambda);
    return;
  }
  const ShapeAppearance& app = scene.appearance(hit);
  if (app.emission >= 0)
    L += beta * evaluate(scene.emission[static_cast<size_t>(app.emission)], lambda);

  const Material& material = scene.materials[app.material];
  const Vec3 wo = -ray.d;
  const SampledSpectrum rho = evaluate(material.reflectance, lambda);
  const SurfaceBsdf bsdf(material, lambda, rho, hit.ng, wo);

  // Direct light on the diffuse lobe, from every light (one sample each). A fluorescent lobe
  // sees the lights at its lanes' excitation wavelengths.
  if (bsdf.hasDiffuse()) {
    const bool fluorescent = material.reradiation != nullptr;
    const FluorescentShift shift =
        fluorescent ? sampleFluorescentShift(*material.reradiation, lambda, rho, rng)
                    : FluorescentShift{lambda, rho};
    for (int k = 0; k < ctx.lights->count(); ++k) {
      const float uChoice =
          (static_cast<float>(k) + 0.5f) / static_cast<float>(ctx.lights->count());
      LightSample ls;
      if (!ctx.lights->sample(hit.p, uChoice, rng.next2D(), shift.excited, ls)) continue;
      const SampledSpectrum f = shift.albedo * bsdf.diffuseFactor(ls.wi);
      if (f.isBlack()) continue;
      Ray shadow;
      shadow.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, ls.wi);
      shadow.d = ls.wi;
      shadow.tMax = ls.distance * kShadowShorten;
      ++counters.rays;
      if (scene.geometry->occluded(shadow, ls.sphere)) continue;
      // ls.pdf includes the choice probability 1/count; every light is visited, so undo it.
      L += beta * f * ls.radiance * (1.0f / (ls.pdf * static_cast<float>(ctx.lights->count())));
    }
  }
  if (bounce >= scene.settings.depth) return;

  auto spawn = [&](const Vec3& wi, const SampledSpectrum& weight, bool hero) {
    if (weight.isBlack()) return;
    Ray next;
    next.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, wi);
    next.d = wi;
    whitted(ctx, next, lambda, hero && !heroOnlyPath ? heroOnly(beta * weight) : beta * weight,
            bounce + 1, heroOnlyPath || hero, rng, counters, L);
  };

  if (material.kind == MaterialKind::Mixture) {
    if (material.roughness < 1 && dot(wo, bsdf.normal()) > 0)
      spawn(reflect(wo, bsdf.normal()), rho * (1 - material.roughness), false);
    return;
  }
  // Fresnel split: both the reflected and the refracted ray are traced.
  const float cosO = dot(wo, hit.ng);
  const bool entering = cosO > 0;
  const Vec3 n = entering ? hit.ng : -hit.ng;
  const bool dispersive = material.ior.dispersive();
  SampledSpectrum fr, tr;
  float etaHero = 1;
  for (int i = 0; i < kLanes; ++i) {
    const float ior = static_cast<float>(material.ior.at(lambda.lambda[i]));
    const float eta = entering ? ior : 1.0f / ior;
    if (i == 0) etaHero = eta;
    fr[i] = fresnelDielectric(std::abs(cosO), eta);
    tr[i] = (1 - fr[i]) / (eta * eta);
  }
  spawn(reflect(wo, n), rho * fr, false);
  Vec3 wt;
  if (refract(wo, n, etaHero, wt)) spawn(normalize(wt), rho * tr, dispersive);
}

} // namespace

SampledSpectrum traceWhitted(const IntegratorContext& ctx, const Ray& ray,
                             const SampledWavelengths& lambda, PixelSampleStream& rng,
                             TraceCounters& counters) {
  SampledSpectrum L;
  whitted(ctx, ray, lambda, SampledSpectrum::filled(1.0f), 0, false, rng, counters, L);
  return L;
}

} // namespace nx
