// tracePathGradients: the radiance of a path and its derivatives' tape. The walk's fluorescent
// variants compile in trace_gradients_fluorescent.cpp (the largest instantiations, split so
// that both cores build them).
#include "integrators/path_walk.h"

namespace nx {

// (trace_gradients_fluorescent.cpp)
void traceGradientsFluorescent(const IntegratorContext& ctx, const Ray& ray,
                               const SampledWavelengths& lambda, PixelSampleStream& rng,
                               TraceCounters& counters, GradientSink& sink);

SampledSpectrum tracePathGradients(const IntegratorContext& ctx, Ray ray,
                                   const SampledWavelengths& lambda, PixelSampleStream& rng,
                                   TraceCounters& counters, GradientTape& tape) {
  GradientSink sink;
  sink.tape = &tape;
  sink.tangents = ctx.gradients->tangents;
  if (ctx.fluorescence)
    traceGradientsFluorescent(ctx, ray, lambda, rng, counters, sink);
  else
    path_walk::traceMediaVariant<false, false>(ctx, ray, lambda, rng, counters, sink);
  return sink.L;
}

} // namespace nx
