// traceWhiteReference: the path with its first surface replaced by a white Lambertian.
#include "integrators/path_walk.h"

namespace nx {

SampledSpectrum traceWhiteReference(const IntegratorContext& ctx, Ray ray,
                                    const SampledWavelengths& lambda, PixelSampleStream& rng,
                                    TraceCounters& counters) {
  if (ctx.scene->relight.enabled) {
    // Built with unit spectra: the groups' spectra applied per contribution, nothing recorded.
    static const ComponentLayout none;
    RelightSink sink;
    sink.components.layout = &none;
    sink.spectra = &ctx.scene->relight.ofSource;
    path_walk::traceVariant<true>(ctx, ray, lambda, rng, counters, sink);
    return sink.components.L;
  }
  RadianceSink sink;
  path_walk::traceVariant<true>(ctx, ray, lambda, rng, counters, sink);
  return sink.L;
}

} // namespace nx
