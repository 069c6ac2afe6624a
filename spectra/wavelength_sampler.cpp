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
  if (!(minNm >= 200 && maxNm > minNm && maxNm <= 1100))
    throw Error("wavelength range must satisfy 200 <= min < max <= 1100 nm, found " +
                std::to_string(minNm) + "-" + std::to_string(maxNm) + " nm");
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
  // so each lane costs one logarithm. Single precision suffices: |t| <= tanh(k 562 nm) = 0.9965
  // within 200-1100 nm, so 1 - |t| keeps 15 bits and the wavelength errs by < 0.01 nm; the
  // pdf is that of the wavelength actually returned to the same precision.
  SampledWavelengths w;
  const float tanhMin = static_cast<float>(tanhMin_), tanhRange = static_cast<float>(tanhRange_);
  const float minNm = static_cast<float>(min_), maxNm = static_cast<float>(max_);
  constexpr float k = static_cast<float>(kSharpness), centre = static_cast<float>(kCentre);
  const float pdfScale = k / tanhRange;
  for (int i = 0; i < kLanes; ++i) {
    float ui = u + static_cast<float>(i) / static_cast<float>(kLanes);
    if (ui >= 1.0f) ui -= 1.0f;
    const float t = std::clamp(tanhMin + ui * tanhRange, -1.0f + 1e-7f, 1.0f - 1e-7f);
    const float l = centre + 0.5f / k * std::log((1.0f + t) / (1.0f - t));
    w.lambda[i] = std::fmin(std::fmax(l, minNm), maxNm);
    w.pdf[i] = pdfScale * (1.0f - t * t);
  }
  return w;
}

} // namespace nx
