// tracePathRelightable: the path of a relightable render, recording its transport.
#include "integrators/path_walk.h"

namespace nx {

SampledSpectrum tracePathRelightable(const IntegratorContext& ctx, Ray ray,
                                     const SampledWavelengths& lambda, PixelSampleStream& rng,
                                     TraceCounters& counters, const ComponentLayout& layout,
                                     SampledSpectrum* layers, RelightRecorder& recorder) {
  RelightSink sink;
  sink.components.layers = layers;
  sink.components.layout = &layout;
  sink.recorder = &recorder;
  sink.spectra = recorder.spectra;
  path_walk::traceVariant<false>(ctx, ray, lambda, rng, counters, sink);
  return sink.components.L;
}

} // namespace nx
