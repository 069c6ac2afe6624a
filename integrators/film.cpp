#include "integrators/film.h"

#include <cmath>

namespace nx {

Film::Film(int width, int height, const PixelRect& rect, const SpectralBands& bands)
    : width_(width), height_(height), rect_(rect), bands_(bands), nBands_(bands.count()) {
  const size_t pixels = static_cast<size_t>(rect.width()) * static_cast<size_t>(rect.height());
  bandSums_.assign(pixels * static_cast<size_t>(nBands_), 0.0);
  xyzSums_.assign(pixels * 3, 0.0);
  counts_.assign(pixels, 0);
}

Film::Pixel Film::newPixel() const {
  Pixel p;
  p.bands.assign(static_cast<size_t>(nBands_), 0.0);
  return p;
}

bool Film::addSample(Pixel& pixel, const SampledWavelengths& lambda,
                     const SampledSpectrum& L) const {
  ++pixel.samples;
  for (int i = 0; i < kLanes; ++i)
    if (!std::isfinite(L[i])) return false;
  const double bandScale = 1.0 / bands_.stepNm;
  for (int i = 0; i < kLanes; ++i) {
    const double w = WavelengthSampler::laneWeight(lambda, i);
    if (w == 0 || L[i] == 0) continue;
    const double v = static_cast<double>(L[i]) * w;
    const int b = bands_.bandOf(lambda.lambda[i]);
    if (b >= 0) pixel.bands[static_cast<size_t>(b)] += v * bandScale;
    const Xyz cmf = cieCmf(lambda.lambda[i]);
    pixel.xyz[0] += v * cmf.x / kCieYIntegral;
    pixel.xyz[1] += v * cmf.y / kCieYIntegral;
    pixel.xyz[2] += v * cmf.z / kCieYIntegral;
  }
  return true;
}

void Film::add(int x, int y, const Pixel& pixel) {
  const size_t i = index(x, y);
  for (int b = 0; b < nBands_; ++b)
    bandSums_[i * nBands_ + b] += pixel.bands[static_cast<size_t>(b)];
  for (int c = 0; c < 3; ++c) xyzSums_[i * 3 + c] += pixel.xyz[c];
  counts_[i] += pixel.samples;
}

void Film::setFromMeans(int x, int y, const float* bandMeans, const double xyzMean[3],
                        uint32_t samples) {
  const size_t i = index(x, y);
  for (int b = 0; b < nBands_; ++b)
    bandSums_[i * nBands_ + b] = static_cast<double>(bandMeans[b]) * samples;
  for (int c = 0; c < 3; ++c) xyzSums_[i * 3 + c] = xyzMean[c] * samples;
  counts_[i] = samples;
}

double Film::bandMean(int x, int y, int b) const {
  const size_t i = index(x, y);
  return counts_[i] ? bandSums_[i * nBands_ + b] / counts_[i] : 0.0;
}

Xyz Film::xyzMean(int x, int y) const {
  const size_t i = index(x, y);
  if (!counts_[i]) return {};
  return {xyzSums_[i * 3] / counts_[i], xyzSums_[i * 3 + 1] / counts_[i],
          xyzSums_[i * 3 + 2] / counts_[i]};
}

} // namespace nx
