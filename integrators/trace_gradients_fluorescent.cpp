// The differentiated walk of scenes with fluorescence (tracePathGradients, trace_gradients.cpp).
#include "integrators/path_walk.h"

namespace nx {

/// The gradient walk of a fluorescent scene (with or without media).
void traceGradientsFluorescent(const IntegratorContext& ctx, const Ray& ray,
                               const SampledWavelengths& lambda, PixelSampleStream& rng,
                               TraceCounters& counters, GradientSink& sink) {
  path_walk::traceMediaVariant<true, false>(ctx, ray, lambda, rng, counters, sink);
}

} // namespace nx
