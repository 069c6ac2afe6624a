#include "io/exr_write_cost.h"

#include <tbb/global_control.h>

#include <algorithm>

#include "io/spectral_exr.h"

namespace nx {

ExrImageShape shapeOf(const SpectralImage& image) {
  ExrImageShape s;
  s.width = image.width, s.height = image.height, s.bands = image.bands.count();
  s.xyz = !image.xyz.empty();
  s.bandVariance = !image.bandVariance.empty();
  s.yVariance = !image.yVariance.empty();
  s.sampleCount = !image.sampleCount.empty();
  s.white = !image.white.empty();
  s.ids = !image.objectId.empty();
  s.depth = !image.depth.empty();
  s.layers = static_cast<int>(image.layers.size());
  s.layerVariances = std::all_of(image.layers.begin(), image.layers.end(),
                                 [](const ImageLayer& l) { return !l.variances.empty(); });
  s.relightSources = image.relight.sources.size();
  s.relightPlanes = s.relightSources * image.relight.entries.size();
  s.relightBins = image.relight.present() ? static_cast<size_t>(image.relight.grid.bins) : 0;
  return s;
}

size_t exrChannelCount(const ExrImageShape& s) {
  const size_t nb = static_cast<size_t>(s.bands);
  return nb + 3 + (s.xyz ? 3 : 0) + (s.bandVariance ? nb : 0) + (s.yVariance ? 1 : 0) +
         (s.white ? nb : 0) + (s.depth ? 1 : 0) +
         static_cast<size_t>(s.layers) * nb * (s.layerVariances ? 2 : 1) + 2 * s.relightPlanes +
         (s.sampleCount ? 1 : 0) + (s.ids ? 2 : 0);
}

int exrWriterThreads(double chunkBytes) {
  const int threads = static_cast<int>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  return chunkBytes > 64.0 * (1 << 20) ? 0 : threads;
}

double exrWriteBytes(const ExrImageShape& s, const ExrEncoding& encoding, bool halfFloats) {
  const ExrCompression c = encoding.compression.value_or(defaultExrCompression(halfFloats));
  const size_t channels = exrChannelCount(s);
  const size_t uints = (s.sampleCount ? 1 : 0) + (s.ids ? 2 : 0);
  const double lineBytes = static_cast<double>(s.width) *
                           (static_cast<double>(channels - uints) * (halfFloats ? 2.0 : 4.0) +
                            4.0 * static_cast<double>(uints));
  const double chunkBytes = lineBytes * exrChunkLines(c);
  const int buffers = std::max(1, 2 * exrWriterThreads(chunkBytes));
  // Per channel: the header's channel list and OpenEXR's copy of it, the frame buffer (a map
  // node with a 256-byte name each), the writer's slice table, the names themselves.
  constexpr double kBytesPerChannel = 1200;
  const double halfCopies = halfFloats ? static_cast<double>(s.width) * s.height *
                                             static_cast<double>(channels - uints) * 2.0
                                       : 0.0;
  // The transport's spectra as text attributes (about 16 bytes per number).
  const double attributes = 16.0 * static_cast<double>(s.relightBins * s.relightSources);
  return buffers * chunkBytes * (1 + exrCompressorBuffers(c)) +
         kBytesPerChannel * static_cast<double>(channels) + halfCopies + attributes;
}

} // namespace nx
