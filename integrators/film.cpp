#include "integrators/film.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace nx {

Film::Film(int width, int height, const PixelRect& rect, const Sensor& bands, bool whiteReference)
    : width_(width), height_(height), rect_(rect), bands_(bands), nBands_(bands.count()),
      responses_(bands) {
  const CieTables& cie = cieTables();
  cmf_.assign(3 * (kCieSamples + 1), 0.0f);
  for (int i = 0; i < kCieSamples; ++i) {
    cmf_[3 * i] = static_cast<float>(cie.xBar[i] / kCieYIntegral);
    cmf_[3 * i + 1] = static_cast<float>(cie.yBar[i] / kCieYIntegral);
    cmf_[3 * i + 2] = static_cast<float>(cie.zBar[i] / kCieYIntegral);
  }
  const size_t pixels = static_cast<size_t>(rect.width()) * static_cast<size_t>(rect.height());
  bandSums_.assign(pixels * static_cast<size_t>(nBands_), 0.0);
  bandOddSums_.assign(pixels * static_cast<size_t>(nBands_), 0.0);
  xyzSums_.assign(pixels * 3, 0.0);
  yOddSums_.assign(pixels, 0.0);
  oddCounts_.assign(pixels, 0);
  counts_.assign(pixels, 0);
  if (whiteReference) whiteSums_.assign(pixels * static_cast<size_t>(nBands_), 0.0);
}

namespace {
// True when every lane is finite (a sum of floats in double cannot overflow: it is non-finite
// only through a lane).
bool allFinite(const SampledSpectrum& L) {
  double sum = 0;
  for (int i = 0; i < kLanes; ++i) sum += static_cast<double>(L[i]);
  return std::isfinite(sum);
}
} // namespace

void Film::setLayers(std::vector<std::string> names) {
  layerNames_ = std::move(names);
  const size_t n = counts_.size() * layerNames_.size() * static_cast<size_t>(nBands_);
  layerSums_.assign(n, 0.0);
  layerOddSums_.assign(n, 0.0);
}

void Film::setRelight(std::shared_ptr<const RelightPattern> pattern,
                      std::vector<std::string> sources, std::vector<std::vector<double>> spectra) {
  relightPattern_ = std::move(pattern);
  relightSourceNames_ = relightPattern_ ? std::move(sources) : std::vector<std::string>();
  relightSourceSpectra_ = relightPattern_ ? std::move(spectra) : std::vector<std::vector<double>>();
  const size_t n = relightPattern_ ? counts_.size() * relightSourceNames_.size() *
                                         static_cast<size_t>(relightPattern_->size())
                                   : 0;
  relightSums_.assign(n, 0.0f);
  relightOddSums_.assign(n, 0.0f);
}

Film::Pixel Film::newPixel() const {
  Pixel p;
  const size_t relight =
      relightPattern_ ? static_cast<size_t>(relightSources()) * relightPattern_->size() : 0;
  for (auto& r : p.relight) r.assign(relight, 0.0);
  for (auto& b : p.bands) b.assign(static_cast<size_t>(nBands_), 0.0);
  for (auto& l : p.layers) l.assign(layerNames_.size() * static_cast<size_t>(nBands_), 0.0);
  if (hasWhite()) p.white.assign(static_cast<size_t>(nBands_), 0.0);
  p.aov.assign(static_cast<size_t>(aovChannels_), 0.0);
  return p;
}

bool Film::addSample(Pixel& pixel, const SampledWavelengths& lambda, const SampledSpectrum& L,
                     bool odd) const {
  const int r = odd ? 1 : 0;
  ++pixel.samples[r];
  if (!allFinite(L)) return false;
  double* bandSums = pixel.bands[r].data();
  double* xyz = pixel.xyz[r];
  // Each lane adds its estimate to the bands that respond at its wavelength
  // (L R_b / integral(R_b)) and to XYZ (L * cmf / integral(y-bar)), weighted 1 / (kLanes pdf).
  for (int i = 0; i < kLanes; ++i) {
    const float v = L[i] * WavelengthSampler::laneWeight(lambda, i);
    if (v == 0) continue;
    const float nm = lambda.lambda[i];
    responses_.forEach(nm, [&](int b, float w) { bandSums[b] += static_cast<double>(v * w); });
    const float cx = nm - static_cast<float>(kCieMinNm);
    if (!(cx >= 0 && cx <= static_cast<float>(kCieSamples - 1))) continue;
    const int k = static_cast<int>(cx);
    const float f = cx - static_cast<float>(k);
    const float* c = &cmf_[3 * static_cast<size_t>(k)]; // c[3..5]: the next nm (zero past 830)
    xyz[0] += static_cast<double>(v * (c[0] + (c[3] - c[0]) * f));
    xyz[1] += static_cast<double>(v * (c[1] + (c[4] - c[1]) * f));
    xyz[2] += static_cast<double>(v * (c[2] + (c[5] - c[2]) * f));
  }
  return true;
}

void Film::addLayerSamples(Pixel& pixel, const SampledWavelengths& lambda,
                           const SampledSpectrum* layers, bool odd) const {
  double* sums = pixel.layers[odd ? 1 : 0].data();
  for (int i = 0; i < kLanes; ++i) {
    const float weight = WavelengthSampler::laneWeight(lambda, i);
    responses_.forEach(lambda.lambda[i], [&](int b, float w) {
      for (size_t l = 0; l < layerNames_.size(); ++l) {
        const float v = layers[l][i] * weight;
        if (v != 0) sums[l * static_cast<size_t>(nBands_) + static_cast<size_t>(b)] += v * w;
      }
    });
  }
}

SampledSpectrum Film::adjointWeights(const SampledWavelengths& lambda, const float* adjoint) const {
  SampledSpectrum out;
  for (int i = 0; i < kLanes; ++i) {
    float sum = 0;
    responses_.forEach(lambda.lambda[i], [&](int b, float w) { sum += adjoint[b] * w; });
    out[i] = sum * WavelengthSampler::laneWeight(lambda, i);
  }
  return out;
}

uint64_t Film::addRelightSamples(Pixel& pixel, const SampledWavelengths& lambda,
                                 const std::vector<RelightContribution>& contributions,
                                 bool odd) const {
  double* sums = pixel.relight[odd ? 1 : 0].data();
  const RelightPattern& pattern = *relightPattern_;
  const size_t perGroup = static_cast<size_t>(pattern.size());
  uint64_t missed = 0;
  for (const RelightContribution& c : contributions) {
    const float v = c.value * WavelengthSampler::laneWeight(lambda, c.lane);
    const float nm = lambda.lambda[c.lane];
    double* group = sums + c.group * perGroup;
    responses_.forEach(nm, [&](int b, float w) {
      const int e = pattern.index(b, c.bin);
      if (e < 0) {
        ++missed;
        return;
      }
      const double add = static_cast<double>(v * w);
      group[e] += add;
      // Fluoresced light in a pair reflected light also reaches: its part kept beside.
      // (Reflected light off the diagonal, or fluoresced light on it without a part, would
      // be split wrongly: counted as missed, which the tests require to be none.)
      const bool diagonal = pattern.entries()[static_cast<size_t>(e)].diagonal != 0;
      if (!c.shifted) {
        missed += !diagonal;
      } else if (diagonal) {
        const int f = pattern.fluorescedIndex(b, c.bin);
        if (f < 0)
          ++missed;
        else
          group[f] += add;
      }
    });
  }
  return missed;
}

bool Film::addWhiteSample(Pixel& pixel, const SampledWavelengths& lambda,
                          const SampledSpectrum& L) const {
  if (!allFinite(L)) return false;
  double* white = pixel.white.data();
  for (int i = 0; i < kLanes; ++i) {
    const float v = L[i] * WavelengthSampler::laneWeight(lambda, i);
    if (v == 0) continue;
    responses_.forEach(lambda.lambda[i],
                       [&](int b, float w) { white[b] += static_cast<double>(v * w); });
  }
  return true;
}

double Film::whiteMean(int x, int y, int b) const {
  const size_t i = index(x, y);
  return counts_[i] && hasWhite() ? whiteSums_[i * nBands_ + b] / counts_[i] : 0.0;
}

void Film::setAovs(std::vector<AovKind> kinds) {
  int channels = 0;
  for (AovKind k : kinds) channels += aovChannelCount(k, nBands_);
  aovKinds_ = std::move(kinds);
  aovChannels_ = channels;
  aovSums_.assign(counts_.size() * static_cast<size_t>(channels), 0.0);
}

void Film::setAovFromMeans(int x, int y, const float* means) {
  const size_t i = index(x, y), n = static_cast<size_t>(aovChannels_);
  for (size_t c = 0; c < n; ++c) aovSums_[i * n + c] = static_cast<double>(means[c]) * counts_[i];
}

void Film::add(int x, int y, const Pixel& pixel) {
  const size_t i = index(x, y);
  const size_t na = static_cast<size_t>(aovChannels_);
  for (size_t c = 0; c < na; ++c) aovSums_[i * na + c] += pixel.aov[c];
  if (hasWhite())
    for (int b = 0; b < nBands_; ++b) whiteSums_[i * nBands_ + b] += pixel.white[b];
  for (int b = 0; b < nBands_; ++b) {
    const double even = pixel.bands[0][static_cast<size_t>(b)],
                 odd = pixel.bands[1][static_cast<size_t>(b)];
    bandSums_[i * nBands_ + b] += even + odd;
    bandOddSums_[i * nBands_ + b] += odd;
  }
  for (int c = 0; c < 3; ++c) xyzSums_[i * 3 + c] += pixel.xyz[0][c] + pixel.xyz[1][c];
  const size_t nl = layerNames_.size() * static_cast<size_t>(nBands_);
  for (size_t k = 0; k < nl; ++k) {
    layerSums_[i * nl + k] += pixel.layers[0][k] + pixel.layers[1][k];
    layerOddSums_[i * nl + k] += pixel.layers[1][k];
  }
  const size_t nr = pixel.relight[0].size();
  for (size_t k = 0; k < nr; ++k) {
    relightSums_[i * nr + k] += static_cast<float>(pixel.relight[0][k] + pixel.relight[1][k]);
    relightOddSums_[i * nr + k] += static_cast<float>(pixel.relight[1][k]);
  }
  yOddSums_[i] += pixel.xyz[1][1];
  oddCounts_[i] += pixel.samples[1];
  counts_[i] += pixel.samples[0] + pixel.samples[1];
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
                        uint32_t oddSamples, const float* whiteMeans) {
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
  if (hasWhite())
    for (int b = 0; b < nBands_; ++b)
      whiteSums_[i * nBands_ + b] = whiteMeans ? whiteMeans[b] * n : 0.0;
  yOddSums_[i] = (xyzMean[1] - std::sqrt(std::max(0.0, yVariance))) * nOdd;
  counts_[i] = samples;
  oddCounts_[i] = oddSamples;
}

void Film::setLayerFromMeans(int x, int y, int l, const float* means, const float* variances) {
  // As setFromMeans: the odd replicate rebuilt from the variance (its size, not its sign).
  const size_t i = index(x, y), nb = static_cast<size_t>(nBands_);
  const size_t at = (i * layerNames_.size() + static_cast<size_t>(l)) * nb;
  const double n = counts_[i], nOdd = oddCounts_[i];
  for (size_t b = 0; b < nb; ++b) {
    layerSums_[at + b] = static_cast<double>(means[b]) * n;
    layerOddSums_[at + b] =
        (means[b] - std::sqrt(variances ? std::max(0.0f, variances[b]) : 0.0f)) * nOdd;
  }
}

double Film::layerMean(int x, int y, int l, int b) const {
  const size_t i = index(x, y);
  const size_t k = (i * layerNames_.size() + static_cast<size_t>(l)) * nBands_ + b;
  return counts_[i] ? layerSums_[k] / counts_[i] : 0.0;
}

double Film::layerVariance(int x, int y, int l, int b) const {
  const size_t i = index(x, y);
  const size_t k = (i * layerNames_.size() + static_cast<size_t>(l)) * nBands_ + b;
  return halfDifferenceVariance(layerSums_[k], layerOddSums_[k], counts_[i], oddCounts_[i]);
}

double Film::relightMean(int x, int y, int g, int e) const {
  const size_t i = index(x, y), n = static_cast<size_t>(relightSources()) * relightPattern_->size();
  const size_t k = i * n + static_cast<size_t>(g) * relightPattern_->size() + e;
  return counts_[i] ? relightSums_[k] / static_cast<double>(counts_[i]) : 0.0;
}

double Film::relightHalfDifference(int x, int y, int g, int e) const {
  const size_t i = index(x, y), n = static_cast<size_t>(relightSources()) * relightPattern_->size();
  const size_t k = i * n + static_cast<size_t>(g) * relightPattern_->size() + e;
  const uint32_t count = counts_[i], odd = oddCounts_[i];
  if (odd == 0 || odd >= count) return 0.0;
  const double a = (relightSums_[k] - relightOddSums_[k]) / static_cast<double>(count - odd),
               b = relightOddSums_[k] / static_cast<double>(odd);
  return 0.5 * (a - b);
}

Film Film::cropped(const PixelRect& r) const {
  if (r.x0 < rect_.x0 || r.y0 < rect_.y0 || r.x1 > rect_.x1 || r.y1 > rect_.y1 || r.x1 <= r.x0 ||
      r.y1 <= r.y0)
    throw Error("internal error: a film crop outside the film");
  Film out(width_, height_, r, bands_, hasWhite());
  out.setLayers(layerNames_);
  out.setRelight(relightPattern_, relightSourceNames_, relightSourceSpectra_);
  out.setRelightGuides(relightGuides_);
  out.setAovs(aovKinds_);
  const size_t na = static_cast<size_t>(aovChannels_);
  const size_t nl = layerNames_.size() * static_cast<size_t>(nBands_);
  const size_t nr =
      relightPattern_ ? static_cast<size_t>(relightSources()) * relightPattern_->size() : 0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const size_t i = index(x, y), o = out.index(x, y);
      const size_t nb = static_cast<size_t>(nBands_);
      std::copy_n(&bandSums_[i * nb], nb, &out.bandSums_[o * nb]);
      std::copy_n(&bandOddSums_[i * nb], nb, &out.bandOddSums_[o * nb]);
      if (hasWhite()) std::copy_n(&whiteSums_[i * nb], nb, &out.whiteSums_[o * nb]);
      std::copy_n(aovSums_.data() + i * na, na, out.aovSums_.data() + o * na);
      std::copy_n(&xyzSums_[i * 3], 3, &out.xyzSums_[o * 3]);
      std::copy_n(layerSums_.data() + i * nl, nl, out.layerSums_.data() + o * nl);
      std::copy_n(layerOddSums_.data() + i * nl, nl, out.layerOddSums_.data() + o * nl);
      std::copy_n(relightSums_.data() + i * nr, nr, out.relightSums_.data() + o * nr);
      std::copy_n(relightOddSums_.data() + i * nr, nr, out.relightOddSums_.data() + o * nr);
      out.yOddSums_[o] = yOddSums_[i];
      out.oddCounts_[o] = oddCounts_[i];
      out.counts_[o] = counts_[i];
    }
  return out;
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

double Film::bandRelativeRmsError(int b) const {
  double var = 0, mean = 0;
  for (size_t i = 0; i < counts_.size(); ++i) {
    if (oddCounts_[i] == 0 || oddCounts_[i] >= counts_[i]) return INFINITY;
    var += halfDifferenceVariance(bandSums_[i * nBands_ + b], bandOddSums_[i * nBands_ + b],
                                  counts_[i], oddCounts_[i]);
    mean += bandSums_[i * nBands_ + b] / counts_[i];
  }
  if (!(mean > 0)) return NAN;
  const double pixels = static_cast<double>(counts_.size());
  return std::sqrt(var / pixels) / (mean / pixels);
}

double Film::worstBandRelativeRmsError(double loNm, double hiNm) const {
  double worst = -1;
  for (int b = 0; b < nBands_; ++b) {
    const double c = bands_.centroid(b);
    if (c < loNm || c > hiNm) continue;
    const double e = bandRelativeRmsError(b);
    if (std::isnan(e)) continue;
    worst = std::max(worst, e);
  }
  return worst < 0 ? INFINITY : worst;
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
