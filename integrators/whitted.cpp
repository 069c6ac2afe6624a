#include <algorithm>
#include <cmath>
#include <vector>

#include "core/ray_offset.h"
#include "integrators/fluorescent_vertex.h"
#include "integrators/integrator.h"
#include "integrators/lights/direct_lighting.h"
#include "integrators/materials/bsdf.h"
#include "integrators/materials/fresnel.h"

namespace nx {
namespace {

// One pending ray of the Whitted tree: what it carries and how deep it is.
struct WhittedRay {
  Ray ray;
  SampledSpectrum beta;
  int bounce = 0;
  bool heroOnlyPath = false;
};

// Traces one ray of the tree: adds what it sees directly (emission, background, direct light on
// a diffuse lobe) to L and pushes its reflected and refracted children (refraction first, so
// that the reflection's subtree is traced first, as the recursive form did).
void traceNode(const IntegratorContext& ctx, const WhittedRay& node, int maxDepth,
               const SampledWavelengths& lambda, PixelSampleStream& rng, TraceCounters& counters,
               SampledSpectrum& L, std::vector<WhittedRay>& stack) {
  const RenderScene& scene = *ctx.scene;
  const Ray& ray = node.ray;
  const SampledSpectrum& beta = node.beta;
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
  const SampledSpectrum rho = scene.reflectanceAt(material, hit, lambda);
  SurfaceBsdf bsdf(material, lambda, rho, hit.ng, hit.ns, wo);
  bsdf.orient(hit.dpdu);
  bsdf.setHeroAlone(node.heroOnlyPath);

  // Direct light on the diffuse lobe, from every light (one sample each). A fluorescent lobe
  // sees the lights at its lanes' excitation wavelengths.
  if (bsdf.hasNonSpecular()) {
    const bool fluorescent = material.reradiation != nullptr;
    const FluorescentShift shift =
        fluorescent ? sampleFluorescentShift(*material.reradiation, lambda, rho, rng)
                    : FluorescentShift{lambda, rho};
    auto f = [&](const Vec3& wi) {
      return fluorescent ? shift.albedo * bsdf.diffuseLobe(wi) : bsdf.f(wi);
    };
    auto noPdf = [](const Vec3&) { return 0.0f; };
    for (int k = 0; k < ctx.lights->count(); ++k) {
      const float uTriangle = rng.next1D();
      LightSample ls;
      if (ctx.lights->sampleLight(k, hit.p, uTriangle, rng.next2D(), shift.excited, ls))
        L += beta * directLight(scene, hit, ray.d, ls, f, noPdf, false, counters);
    }
  }
  if (node.bounce >= maxDepth) return;

  auto spawn = [&](const Vec3& wi, const SampledSpectrum& weight, bool hero) {
    if (weight.isBlack()) return;
    WhittedRay next;
    next.ray.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, wi);
    next.ray.d = wi;
    next.beta = hero && !node.heroOnlyPath ? heroOnly(beta * weight) : beta * weight;
    next.bounce = node.bounce + 1;
    next.heroOnlyPath = node.heroOnlyPath || hero;
    stack.push_back(next);
  };

  if (material.kind == MaterialKind::Conductor) {
    // A smooth conductor's mirror ray, weighted by the lanes' Fresnel reflectance; a rough one
    // has only its direct light (above), like the diffuse lobe.
    BsdfSample bs;
    if ((bsdf.lobes() & kSpecularReflection) && bsdf.sample(0, {}, bs))
      spawn(bs.wi, bs.weight, false);
    return;
  }
  if (bsdf.lobes() & (kGlossyReflection | kGlossyTransmission)) return; // rough: direct light only
  if (material.kind == MaterialKind::CoatedDiffuse) {
    // the clear coat's mirror ray, weighted by its Fresnel reflectance
    const float c = dot(wo, bsdf.normal());
    if (c > 0)
      spawn(reflect(wo, bsdf.normal()),
            SampledSpectrum::filled(
                fresnelDielectric(c, static_cast<float>(material.ior.at(lambda.lambda[0])))),
            false);
    return;
  }
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
    fr[i] = dielectricReflectance(material, std::abs(cosO), entering ? 1.0f : ior,
                                  entering ? ior : 1.0f, lambda.lambda[i]);
    tr[i] = (1 - fr[i]) / (eta * eta);
  }
  Vec3 wt;
  if (refract(wo, n, etaHero, wt)) spawn(normalize(wt), rho * tr, dispersive);
  spawn(reflect(wo, n), rho * fr, false);
}

} // namespace

SampledSpectrum traceWhitted(const IntegratorContext& ctx, const Ray& ray,
                             const SampledWavelengths& lambda, PixelSampleStream& rng,
                             TraceCounters& counters) {
  // The tree is traced depth first from an explicit stack (never the call stack: two facing
  // mirrors at <depth> 100000 overflowed it), at most kMaxPathBounces deep like the path
  // tracer, and at most kWhittedRayBudget rays per sample (glass between mirrors branches at
  // every bounce); a sample that reaches the budget keeps what it has and is counted.
  thread_local std::vector<WhittedRay> stack; // reused: no allocation per sample
  stack.clear();
  const int maxDepth = std::min(ctx.scene->settings.depth, kMaxPathBounces);
  SampledSpectrum L;
  stack.push_back({ray, SampledSpectrum::filled(1.0f), 0, false});
  int traced = 0;
  while (!stack.empty()) {
    if (traced++ == kWhittedRayBudget) {
      ++counters.truncated;
      break;
    }
    const WhittedRay node = stack.back();
    stack.pop_back();
    traceNode(ctx, node, maxDepth, lambda, rng, counters, L, stack);
  }
  return L;
}

} // namespace nx
