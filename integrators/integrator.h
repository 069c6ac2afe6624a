#pragma once
// The per-sample light transport estimators: spectral path tracing and Whitted ray tracing.

#include <cstdint>

#include "core/ray.h"
#include "core/sampler.h"
#include "integrators/lights/light_sampler.h"
#include "integrators/path_contributions.h"
#include "integrators/render_scene.h"

namespace nx {

struct GradientContext;
struct GradientTape;

/// How direct light reaches diffuse surfaces in the path tracer.
enum class LightSampling : uint8_t {
  Mis,      ///< next-event estimation and BSDF sampling, combined by the power heuristic
  BsdfOnly, ///< lights are found only by BSDF-sampled rays
  NeeOnly,  ///< lights reach diffuse surfaces by next-event estimation alone (an emitter hit
            ///< after a diffuse bounce counts zero); emitters that next-event estimation
            ///< cannot sample (planes) are still found by BSDF-sampled rays, so the image
            ///< stays unbiased
};

/// Longest path the path tracer follows, far beyond any <depth>: Russian roulette ends paths
/// long before; this only bounds pathological scenes (e.g. a closed mirror box).
inline constexpr int kMaxPathBounces = 1024;

/// Values of a spectrum at the lanes' wavelengths (one dispatch for all lanes).
inline SampledSpectrum evaluate(const Spectrum& s, const SampledWavelengths& lambda) {
  SampledSpectrum out;
  s.evaluate(lambda, out);
  return out;
}

/// Everything a per-sample estimator needs besides the sample itself.
struct IntegratorContext {
  const RenderScene* scene;
  const LightSampler* lights;
  LightSampling lightSampling = LightSampling::Mis;
  bool fluorescence = false; ///< run the fluorescent variant (scenes with fluorescent materials)
  /// Draw excitation wavelengths from the matrix column alone (benchmarks: the strategy before
  /// the light-guided one; RenderOptions::columnOnlyExcitation).
  bool columnOnlyExcitation = false;
  /// The tangents of a differentiated render (tracePathGradients), else null.
  const GradientContext* gradients = nullptr;
};

/// Most rays one camera sample of Whitted ray tracing may trace (its tree branches at every
/// dielectric); a sample that reaches it keeps what it found and is counted as truncated.
inline constexpr int kWhittedRayBudget = 1 << 14;

/// Per-task counters (summed after rendering).
struct TraceCounters {
  uint64_t rays = 0;
  uint64_t truncated = 0;     ///< Whitted samples that reached kWhittedRayBudget
  uint64_t bounceLimited = 0; ///< paths ended by kMaxPathBounces while still carrying light
};

/// Radiance arriving along `ray` at the lanes of `lambda` (spectral path tracing with
/// hero wavelengths, NEE + MIS, Russian roulette after scene depth bounces), to be weighted
/// by the film with lambda's pdfs. After a dispersive refraction the remaining path carries
/// the hero lane alone, scaled by kLanes (see heroOnly()).
SampledSpectrum tracePath(const IntegratorContext& ctx, Ray ray, const SampledWavelengths& lambda,
                          PixelSampleStream& rng, TraceCounters& counters);

/// tracePath that also splits the radiance into the layers of `layout` (path classes, light
/// groups; see ComponentSink), adding to layers[0 .. layout.count) (zeroed by the caller): the
/// same random numbers and the same radiance as tracePath.
SampledSpectrum tracePathComponents(const IntegratorContext& ctx, Ray ray,
                                    const SampledWavelengths& lambda, PixelSampleStream& rng,
                                    TraceCounters& counters, const ComponentLayout& layout,
                                    SampledSpectrum* layers);

/// tracePath that also records on `tape` (cleared by the caller) the log-derivatives of the
/// path's vertices with respect to ctx.gradients' slots, and its contributions
/// (integrators/gradients/path_gradients.h): the same random numbers and radiance as tracePath.
SampledSpectrum tracePathGradients(const IntegratorContext& ctx, Ray ray,
                                   const SampledWavelengths& lambda, PixelSampleStream& rng,
                                   TraceCounters& counters, GradientTape& tape);

/// tracePathComponents for a scene built relightable (RelightSpectra): the radiance and layers
/// with the groups' spectra applied, and every contribution per unit spectrum appended to
/// recorder.contributions (cleared by the caller).
SampledSpectrum tracePathRelightable(const IntegratorContext& ctx, Ray ray,
                                     const SampledWavelengths& lambda, PixelSampleStream& rng,
                                     TraceCounters& counters, const ComponentLayout& layout,
                                     SampledSpectrum* layers, RelightRecorder& recorder);

/// The white reference along `ray`: the radiance a white Lambertian surface (reflectance 1,
/// not emitting) put in place of the first surface hit would reflect towards the camera, lit by
/// the scene as it is (direct and indirect light, path traced as tracePath). Zero where the ray
/// hits nothing.
SampledSpectrum traceWhiteReference(const IntegratorContext& ctx, Ray ray,
                                    const SampledWavelengths& lambda, PixelSampleStream& rng,
                                    TraceCounters& counters);

/// Radiance along `ray` by Whitted ray tracing through the same materials: emission seen
/// directly or through specular chains, direct light on diffuse lobes from every light,
/// Fresnel-split reflection and refraction up to the scene's depth (at most kMaxPathBounces),
/// iteratively, with at most kWhittedRayBudget rays.
SampledSpectrum traceWhitted(const IntegratorContext& ctx, const Ray& ray,
                             const SampledWavelengths& lambda, PixelSampleStream& rng,
                             TraceCounters& counters);

} // namespace nx
