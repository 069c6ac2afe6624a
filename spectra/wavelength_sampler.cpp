#include "spectra/wavelength_sampler.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace nx {
namespace {
constexpr double kSharpness = 0.0072; // 1/nm
constexpr double kCentre = 538.0;     // nm
} // namespace

WavelengthSampler::WavelengthSampler(double minNm, double maxNm) : min_(minNm), max_(maxNm) {
  if (!(minNm > 0 && maxNm > minNm && std::isfinite(maxNm)))
    throw Error("wavelength range must satisfy 0 < min < max, found " + std::to_string(minNm) +
                "-" + std::to_string(maxNm) + " nm");
  tanhMin_ = std::tanh(kSharpness * (min_ - kCentre));
  tanhRange_ = std::tanh(kSharpness * (max_ - kCentre)) - tanhMin_;
}

double WavelengthSampler::wavelength(double u) const {
  // CDF(l) = (tanh(k (l - c)) - tanh(k (min - c))) / tanhRange, inverted.
  const double l = kCentre + std::atanh(tanhMin_ + u * tanhRange_) / kSharpness;
  return std::fmin(std::fmax(l, min_), max_);
}

double WavelengthSampler::pdf(double nm) const {
  if (nm < min_ || nm > max_) return 0.0;
  const double c = std::cosh(kSharpness * (nm - kCentre));
  return kSharpness / (c * c * tanhRange_);
}

SampledWavelengths WavelengthSampler::sample(float u) const {
  // With t = tanh(k (l - c)) = tanhMin + u' tanhRange for the lane's primary sample u':
  // l = c + atanh(t) / k and pdf = k (1 - t^2) / tanhRange (since 1 / cosh^2 = 1 - tanh^2),
  // so each lane costs one logarithm.
  SampledWavelengths w;
  for (int i = 0; i < kLanes; ++i) {
    double ui = u + static_cast<double>(i) / kLanes;
    if (ui >= 1.0) ui -= 1.0;
    const double t = std::clamp(tanhMin_ + ui * tanhRange_, -1.0 + 1e-15, 1.0 - 1e-15);
    const double l = kCentre + 0.5 * std::log((1.0 + t) / (1.0 - t)) / kSharpness;
    w.lambda[i] = static_cast<float>(std::fmin(std::fmax(l, min_), max_));
    w.pdf[i] = static_cast<float>(kSharpness * (1.0 - t * t) / tanhRange_);
  }
  return w;
}

} // namespace nx
