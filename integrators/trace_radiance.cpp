// tracePath: the radiance of a path (its own translation unit: the walk's instantiations for
// each sink compile in parallel).
#include "integrators/path_walk.h"

namespace nx {

SampledSpectrum tracePath(const IntegratorContext& ctx, Ray ray, const SampledWavelengths& lambda,
                          PixelSampleStream& rng, TraceCounters& counters) {
  RadianceSink sink;
  path_walk::traceVariant<false>(ctx, ray, lambda, rng, counters, sink);
  return sink.L;
}

} // namespace nx
