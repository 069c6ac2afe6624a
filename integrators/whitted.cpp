#include <algorithm>
#include <cmath>
#include <vector>

#include "core/ray_offset.h"
#include "integrators/fluorescent_vertex.h"
#include "integrators/integrator.h"
#include "integrators/lights/direct_lighting.h"
#include "integrators/materials/bsdf.h"

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
    for (int e = 0; e < ctx.lights->environmentCount(); ++e)
      L += beta * ctx.lights->environmentRadiance(e, ray.d, lambda);
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
    const float concentration = scene.concentrationAt(material, hit);
    const FluorescentShift shift =
        fluorescent ? sampleFluorescentShift(*material.reradiation, lambda, rho, rng,
                                             material.concentration ? &concentration : nullptr)
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

  // The delta lobes, each followed with its full weight; pushed transmission first so that
  // the reflection's subtree is traced first, as the recursive form did. Glossy and diffuse
  // lobes have only their direct light (above).
  SpecularLobe lobes[2];
  for (int i = bsdf.specularLobes(lobes) - 1; i >= 0; --i)
    spawn(lobes[i].wi, lobes[i].weight, lobes[i].heroOnly);
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
