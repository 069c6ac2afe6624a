#include <cmath>

#include "core/ray_offset.h"
#include "integrators/fluorescent_vertex.h"
#include "integrators/integrator.h"
#include "integrators/lights/direct_lighting.h"
#include "integrators/materials/bsdf.h"
#include "integrators/sampling.h"

namespace nx {
namespace {

// The white reference's surface: a Lambertian reflector of reflectance 1.
const Material& whiteLambertian() {
  static const Material white{MaterialKind::Mixture,
                              1.0f,
                              IorModel::constant(1.5),
                              Spectrum(ConstantSpectrum{1.0}),
                              std::nullopt,
                              nullptr,
                              nullptr};
  return white;
}

// kFluorescence: compiled in only for scenes with fluorescent materials, so that other
// scenes run exactly the code they would without the feature.
// kWhite: the first surface hit is replaced by a white Lambertian reflector that does not emit
// (the white-reference AOV); later bounces see the scene as it is.
template <bool kFluorescence, bool kWhite>
SampledSpectrum tracePathImpl(const IntegratorContext& ctx, Ray ray,
                              const SampledWavelengths& lambda, PixelSampleStream& rng,
                              TraceCounters& counters) {
  const RenderScene& scene = *ctx.scene;
  const int rouletteStart = scene.settings.depth;
  // lambda: the sensor wavelengths (where the film accumulates); current: what lights and
  // materials are evaluated at (they differ after a fluorescent shift).
  SampledWavelengths current = lambda;
  SampledSpectrum L, beta = SampledSpectrum::filled(1.0f);
  // Russian roulette looks at beta * rrScale: the throughput without the radiance scaling
  // 1 / eta^2 of refractions (a lossless path through glass keeps probability 1, as in pbrt-v4
  // and Mitsuba 3) and without the factor kLanes of a hero-only path.
  float rrScale = 1;
  bool heroAlone = kLanes == 1; // the secondary lanes were terminated (dispersion)
  bool specular = true;         // the previous bounce was specular (or the camera)
  float prevPdf = 0;
  Vec3 prevP = ray.o;

  for (int bounce = 0;; ++bounce) {
    SurfaceHit hit;
    ++counters.rays;
    // Weight of an emitter found by this BSDF-sampled ray that next-event estimation could
    // also have sampled, with density lightPdf.
    auto emitterWeight = [&](float lightPdf) {
      if (specular || ctx.lightSampling == LightSampling::BsdfOnly || !(lightPdf > 0)) return 1.0f;
      return ctx.lightSampling == LightSampling::NeeOnly ? 0.0f : powerHeuristic(prevPdf, lightPdf);
    };
    if (!scene.geometry->intersect(ray, hit)) {
      if (scene.background)
        L += beta * evaluate(*scene.background, current) *
             (specular ? 1.0f : emitterWeight(ctx.lights->pdfBackground(prevP)));
      break;
    }
    const ShapeAppearance& app = scene.appearance(hit);
    const bool whiteHere = kWhite && bounce == 0;
    if (app.emission >= 0 && !whiteHere) {
      const float w = specular ? 1.0f : emitterWeight(ctx.lights->pdf(prevP, hit, ray.d));
      if (w > 0)
        L += beta * evaluate(scene.emission[static_cast<size_t>(app.emission)], current) * w;
    }
    if (bounce >= kMaxPathBounces) break;

    const Material& material = whiteHere ? whiteLambertian() : scene.materials[app.material];
    const Vec3 wo = -ray.d;
    const SampledSpectrum rho = scene.reflectanceAt(material, hit, current);
    const SurfaceBsdf bsdf(material, current, rho, hit.ng, hit.ns, wo);

    // A fluorescent diffuse lobe: every lane's excitation wavelength is chosen once, for both
    // next-event estimation and the continuation through the diffuse lobe.
    [[maybe_unused]] FluorescentShift shift;
    [[maybe_unused]] bool fluorescent = false;
    if constexpr (kFluorescence) {
      if (material.reradiation && bsdf.hasNonSpecular()) {
        shift = sampleFluorescentShift(*material.reradiation, current, rho, rng);
        fluorescent = true;
      }
    }

    if (bsdf.hasNonSpecular() && ctx.lightSampling != LightSampling::BsdfOnly &&
        ctx.lights->count() > 0) {
      const float uChoice = rng.next1D();
      const Sample2 uLight = rng.next2D();
      LightSample ls;
      const SampledWavelengths& lit = fluorescent ? shift.excited : current;
      if (ctx.lights->sample(hit.p, uChoice, uLight, lit, ls)) {
        auto f = [&](const Vec3& wi) {
          return fluorescent ? shift.albedo * bsdf.diffuseFactor(wi) : bsdf.f(wi);
        };
        auto pdf = [&](const Vec3& wi) { return bsdf.pdf(wi); };
        L += beta * directLight(scene, hit, ray.d, ls, f, pdf,
                                ctx.lightSampling != LightSampling::NeeOnly, counters);
      }
    }

    BsdfSample bs;
    const float uLobe = rng.next1D();
    const Sample2 uDir = rng.next2D();
    if (!bsdf.sample(uLobe, uDir, bs)) break;
    if constexpr (kFluorescence) {
      if (fluorescent && !bs.specular) { // the diffuse lobe re-radiates; the mirror lobe does not
        bs.weight = shift.albedo;
        current = shift.excited;
      }
    }
    beta *= bs.weight;
    rrScale *= bs.eta * bs.eta;
    if (bs.terminateSecondary && !heroAlone) {
      // From here on the hero's estimator stands alone; what L holds keeps its lane weights.
      beta = heroOnly(beta);
      rrScale *= 1.0f / static_cast<float>(kLanes);
      heroAlone = true;
    }
    specular = bs.specular;
    prevPdf = bs.pdf;
    prevP = hit.p;

    // Russian roulette after <depth> bounces, re-weighted by 1/q: unbiased.
    if (bounce + 1 >= rouletteStart) {
      const float q = std::min(1.0f, beta.maxValue() * rrScale);
      const float u = rng.next1D();
      if (!(q > 0) || u >= q) break;
      beta *= 1.0f / q;
    }
    if (beta.isBlack()) break;
    ray.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, bs.wi);
    ray.d = bs.wi;
    ray.tMin = 0;
    ray.tMax = INFINITY;
  }
  return L;
}

} // namespace

SampledSpectrum tracePath(const IntegratorContext& ctx, Ray ray, const SampledWavelengths& lambda,
                          PixelSampleStream& rng, TraceCounters& counters) {
  return ctx.fluorescence ? tracePathImpl<true, false>(ctx, ray, lambda, rng, counters)
                          : tracePathImpl<false, false>(ctx, ray, lambda, rng, counters);
}

SampledSpectrum traceWhiteReference(const IntegratorContext& ctx, Ray ray,
                                    const SampledWavelengths& lambda, PixelSampleStream& rng,
                                    TraceCounters& counters) {
  return ctx.fluorescence ? tracePathImpl<true, true>(ctx, ray, lambda, rng, counters)
                          : tracePathImpl<false, true>(ctx, ray, lambda, rng, counters);
}

} // namespace nx
