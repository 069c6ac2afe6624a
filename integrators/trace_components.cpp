// tracePathComponents: the radiance of a path split into the layers of a component layout.
#include "integrators/path_walk.h"

namespace nx {

SampledSpectrum tracePathComponents(const IntegratorContext& ctx, Ray ray,
                                    const SampledWavelengths& lambda, PixelSampleStream& rng,
                                    TraceCounters& counters, const ComponentLayout& layout,
                                    SampledSpectrum* layers) {
  ComponentSink sink;
  sink.layers = layers;
  sink.layout = &layout;
  path_walk::traceVariant<false>(ctx, ray, lambda, rng, counters, sink);
  return sink.L;
}

} // namespace nx
