#include "integrators/film.h"

#include <algorithm>
#include <cmath>

namespace nx {

Film::Film(int width, int height, const PixelRect& rect, const SpectralBands& bands)
    : width_(width), height_(height), rect_(rect), bands_(bands), nBands_(bands.count()),
      cie_(&cieTables()) {
  const size_t pixels = static_cast<size_t>(rect.width()) * static_cast<size_t>(rect.height());
  bandSums_.assign(pixels * static_cast<size_t>(nBands_), 0.0);
  bandOddSums_.assign(pixels * static_cast<size_t>(nBands_), 0.0);
  xyzSums_.assign(pixels * 3, 0.0);
  yOddSums_.assign(pixels, 0.0);
  oddCounts_.assign(pixels, 0);
  counts_.assign(pixels, 0);
}

Film::Pixel Film::newPixel() const {
  Pixel p;
  p.bands.assign(static_cast<size_t>(nBands_), 0.0);
  p.bandsOdd.assign(static_cast<size_t>(nBands_), 0.0);
  return p;
}

bool Film::addSample(Pixel& pixel, const SampledWavelengths& lambda, const SampledSpectrum& L,
                     bool odd) const {
  ++pixel.samples;
  pixel.samplesOdd += odd;
  for (int i = 0; i < kLanes; ++i)
    if (!std::isfinite(L[i])) return false;
  const double bandScale = 1.0 / bands_.stepNm;
  // This sample's estimate of each band it touches (at most kLanes bands) and of XYZ.
  int band[kLanes];
  double bandValue[kLanes];
  int touched = 0;
  double xyz[3] = {0, 0, 0};
  for (int i = 0; i < kLanes; ++i) {
    const double w = WavelengthSampler::laneWeight(lambda, i);
    if (w == 0 || L[i] == 0) continue;
    const double v = static_cast<double>(L[i]) * w;
    const int b = bands_.bandOf(lambda.lambda[i]);
    if (b >= 0) {
      int k = 0;
      while (k < touched && band[k] != b) ++k;
      if (k == touched) band[touched] = b, bandValue[touched++] = 0;
      bandValue[k] += v * bandScale;
    }
    const Xyz cmf = cieCmf(*cie_, lambda.lambda[i]);
    xyz[0] += v * cmf.x / kCieYIntegral;
    xyz[1] += v * cmf.y / kCieYIntegral;
    xyz[2] += v * cmf.z / kCieYIntegral;
  }
  for (int k = 0; k < touched; ++k) {
    pixel.bands[static_cast<size_t>(band[k])] += bandValue[k];
    if (odd) pixel.bandsOdd[static_cast<size_t>(band[k])] += bandValue[k];
  }
  for (int c = 0; c < 3; ++c) pixel.xyz[c] += xyz[c];
  if (odd) pixel.yOdd += xyz[1];
  return true;
}

void Film::add(int x, int y, const Pixel& pixel) {
  const size_t i = index(x, y);
  for (int b = 0; b < nBands_; ++b) {
    bandSums_[i * nBands_ + b] += pixel.bands[static_cast<size_t>(b)];
    bandOddSums_[i * nBands_ + b] += pixel.bandsOdd[static_cast<size_t>(b)];
  }
  for (int c = 0; c < 3; ++c) xyzSums_[i * 3 + c] += pixel.xyz[c];
  yOddSums_[i] += pixel.yOdd;
  oddCounts_[i] += pixel.samplesOdd;
  counts_[i] += pixel.samples;
}

namespace {
// Variance of the mean of all samples from the two replicates' sums: ((A - B) / 2)^2.
double halfDifferenceVariance(double sum, double oddSum, uint32_t n, uint32_t nOdd) {
  if (nOdd == 0 || nOdd >= n) return 0.0;
  const double a = (sum - oddSum) / (n - nOdd), b = oddSum / nOdd;
  return 0.25 * (a - b) * (a - b);
}
} // namespace

void Film::setFromMeans(int x, int y, const float* bandMeans, const float* bandVariances,
                        const double xyzMean[3], double yVariance, uint32_t samples,
                        uint32_t oddSamples) {
  // The odd replicate's sum is rebuilt from the stored variance: A - B = 2 sqrt(var) (the sign
  // of the difference is not stored, so the estimate after resuming keeps its size, not its sign).
  const size_t i = index(x, y);
  const double n = samples, nOdd = oddSamples;
  for (int b = 0; b < nBands_; ++b) {
    const double mean = bandMeans[b];
    bandSums_[i * nBands_ + b] = mean * n;
    bandOddSums_[i * nBands_ + b] =
        (mean - std::sqrt(bandVariances ? std::max(0.0f, bandVariances[b]) : 0.0f)) * nOdd;
  }
  for (int c = 0; c < 3; ++c) xyzSums_[i * 3 + c] = xyzMean[c] * n;
  yOddSums_[i] = (xyzMean[1] - std::sqrt(std::max(0.0, yVariance))) * nOdd;
  counts_[i] = samples;
  oddCounts_[i] = oddSamples;
}

double Film::bandVariance(int x, int y, int b) const {
  const size_t i = index(x, y);
  return halfDifferenceVariance(bandSums_[i * nBands_ + b], bandOddSums_[i * nBands_ + b],
                                counts_[i], oddCounts_[i]);
}

double Film::yVariance(int x, int y) const {
  const size_t i = index(x, y);
  return halfDifferenceVariance(xyzSums_[i * 3 + 1], yOddSums_[i], counts_[i], oddCounts_[i]);
}

double Film::relativeRmsError() const {
  double var = 0, mean = 0;
  size_t n = 0;
  for (size_t i = 0; i < counts_.size(); ++i) {
    if (oddCounts_[i] == 0 || oddCounts_[i] >= counts_[i]) return INFINITY;
    var += halfDifferenceVariance(xyzSums_[i * 3 + 1], yOddSums_[i], counts_[i], oddCounts_[i]);
    mean += xyzSums_[i * 3 + 1] / counts_[i];
    ++n;
  }
  if (n == 0 || !(mean > 0)) return INFINITY;
  const double pixels = static_cast<double>(n);
  return std::sqrt(var / pixels) / (mean / pixels);
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
