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
  // CDF(l) = (tanh(k (l - c)) - tanh(k (min - c))) / tanhRange, inverted at j / kSegments.
  const double tanhMin = std::tanh(kSharpness * (min_ - kCentre));
  const double tanhRange = std::tanh(kSharpness * (max_ - kCentre)) - tanhMin;
  knotNm_[0] = min_;
  knotNm_[kSegments] = max_;
  for (int j = 1; j < kSegments; ++j) {
    const double l = kCentre + std::atanh(tanhMin + tanhRange * j / kSegments) / kSharpness;
    knotNm_[j] = std::clamp(l, knotNm_[j - 1], max_);
  }
  for (int j = 0; j < kSegments; ++j) {
    const double width = knotNm_[j + 1] - knotNm_[j];
    segmentPdf_[j] = width > 0 ? static_cast<float>(1.0 / (kSegments * width)) : 0.0f;
  }
}

double WavelengthSampler::wavelength(double u) const {
  const double x = std::clamp(u, 0.0, 1.0) * kSegments;
  const int j = std::min(static_cast<int>(x), kSegments - 1);
  return knotNm_[j] + (x - j) * (knotNm_[j + 1] - knotNm_[j]);
}

double WavelengthSampler::pdf(double nm) const {
  if (nm < min_ || nm > max_) return 0.0;
  const int j =
      static_cast<int>(std::upper_bound(knotNm_.begin(), knotNm_.end(), nm) - knotNm_.begin()) - 1;
  return segmentPdf_[std::clamp(j, 0, kSegments - 1)];
}

SampledWavelengths WavelengthSampler::sample(float u) const {
  SampledWavelengths w;
  for (int i = 0; i < kLanes; ++i) {
    float ui = u + static_cast<float>(i) / static_cast<float>(kLanes);
    if (ui >= 1.0f) ui -= 1.0f;
    const float x = ui * static_cast<float>(kSegments);
    const int j = std::min(static_cast<int>(x), kSegments - 1);
    const double f = static_cast<double>(x) - j;
    w.lambda[i] = static_cast<float>(knotNm_[j] + f * (knotNm_[j + 1] - knotNm_[j]));
    w.pdf[i] = segmentPdf_[j];
  }
  return w;
}

} // namespace nx
