#include "spectra/wavelength_sampler.h"
#include "core/cell_index.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "spectra/cie.h"

namespace nx {
namespace {
constexpr double kSharpness = 0.0072; // 1/nm
constexpr double kCentre = 538.0;     // nm
// Share of the sensor density's lanes drawn from the visible density (for XYZ and the preview).
constexpr double kVisibleShare = 0.5;
} // namespace

double WavelengthSampler::visibleShape(double nm) {
  const double c = std::cosh(kSharpness * (nm - kCentre));
  return 1.0 / (c * c);
}

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

WavelengthSampler::WavelengthSampler(double minNm, double maxNm,
                                     const std::function<double(double)>& density, double gridNm)
    : min_(minNm), max_(maxNm) {
  if (!(minNm >= 200 && maxNm > minNm && maxNm <= 1100))
    throw Error("wavelength range must satisfy 200 <= min < max <= 1100 nm, found " +
                std::to_string(minNm) + "-" + std::to_string(maxNm) + " nm");
  build(density, gridNm);
}

void WavelengthSampler::build(const std::function<double(double)>& density, double gridNm) {
  // The CDF on a fine grid (midpoint rule per cell, linear within a cell), inverted at
  // j / kSegments; each segment then carries its exact share 1 / kSegments of the mass.
  const int cells = std::clamp(static_cast<int>(std::ceil((max_ - min_) / gridNm)), 1, 1 << 21);
  const double h = (max_ - min_) / cells;
  std::vector<double> cdf(static_cast<size_t>(cells) + 1, 0.0);
  for (int k = 0; k < cells; ++k)
    cdf[static_cast<size_t>(k) + 1] =
        cdf[static_cast<size_t>(k)] + std::max(0.0, density(min_ + (k + 0.5) * h)) * h;
  const double total = cdf.back();
  if (!(total > 0) || !std::isfinite(total))
    throw Error("wavelength density: expected a positive integral, found " + std::to_string(total));
  knotNm_[0] = min_;
  knotNm_[kSegments] = max_;
  size_t k = 0;
  for (int j = 1; j < kSegments; ++j) {
    const double target = total * j / kSegments;
    while (k + 1 < cdf.size() - 1 && cdf[k + 1] < target) ++k;
    const double inCell = cdf[k + 1] - cdf[k];
    const double t = inCell > 0 ? std::clamp((target - cdf[k]) / inCell, 0.0, 1.0) : 0.0;
    knotNm_[j] = std::clamp(min_ + (static_cast<double>(k) + t) * h, knotNm_[j - 1], max_);
  }
  for (int j = 0; j < kSegments; ++j) {
    const double width = knotNm_[j + 1] - knotNm_[j];
    segmentPdf_[j] = width > 0 ? static_cast<float>(1.0 / (kSegments * width)) : 0.0f;
  }
}

WavelengthSampler WavelengthSampler::forSensor(const Sensor& sensor, double minNm, double maxNm) {
  // Visible part: the sech^2 density normalised over 360-830 nm (closed form through tanh).
  const double lo = std::max(minNm, static_cast<double>(kCieMinNm)),
               hi = std::min(maxNm, static_cast<double>(kCieMaxNm));
  const double visibleMass =
      (std::tanh(kSharpness * (hi - kCentre)) - std::tanh(kSharpness * (lo - kCentre))) /
      kSharpness;
  auto visible = [&](double nm) {
    return nm >= lo && nm <= hi ? visibleShape(nm) / visibleMass : 0.0;
  };
  // Band part: sum_c w_c Rn_c (Rn_c = R_c / integral R_c). Band c sees the density
  // d_c = integral(p Rn_c) ~ a v_c + (1 - a) w_c q_c, with v_c = integral(visible Rn_c) and
  // q_c = integral(Rn_c^2) (overlaps between bands neglected). The weights fill the bands the
  // visible part leaves short up to a common level D (water filling: w_c = max(0, D - a v_c) /
  // ((1 - a) q_c), sum w_c = 1), so that every band gets the same share of lanes where it can.
  const SensorResponseTable responses(sensor);
  const int n = sensor.count();
  std::vector<double> v(static_cast<size_t>(n), 0.0), q(static_cast<size_t>(n), 0.0);
  const double h = std::min(0.01, 0.25 * sensor.cellNm());
  for (double nm = sensor.minNm() + 0.5 * h; nm < sensor.maxNm(); nm += h)
    responses.forEach(static_cast<float>(nm), [&](int c, float w) {
      v[static_cast<size_t>(c)] += visible(nm) * w * h;
      q[static_cast<size_t>(c)] += static_cast<double>(w) * w * h;
    });
  const double a = kVisibleShare;
  auto weightsAt = [&](double level, std::vector<double>* w) {
    double sum = 0;
    for (size_t c = 0; c < v.size(); ++c) {
      const double wc = q[c] > 0 ? std::max(0.0, level - a * v[c]) / ((1 - a) * q[c]) : 0.0;
      sum += wc;
      if (w) (*w)[c] = wc;
    }
    return sum;
  };
  double levelLo = 0, levelHi = 1;
  // Bounded: a level reaching DBL_MAX means no band has a usable response (every q_c 0).
  for (int i = 0; i < 1100 && !(weightsAt(levelHi, nullptr) >= 1); ++i) levelHi *= 2;
  if (!(weightsAt(levelHi, nullptr) >= 1 && std::isfinite(weightsAt(levelHi, nullptr))))
    throw Error("sensor '" + sensor.summary() +
                "': expected band responses the wavelength sampler can weight, found none with "
                "a finite, non-zero tabulated response");
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (levelLo + levelHi);
    (weightsAt(mid, nullptr) < 1 ? levelLo : levelHi) = mid;
  }
  std::vector<double> w(static_cast<size_t>(n));
  const double total = weightsAt(levelHi, &w);
  for (double& wc : w) wc /= total;
  auto density = [&](double nm) {
    double bands = 0;
    responses.forEach(static_cast<float>(nm),
                      [&](int c, float r) { bands += w[static_cast<size_t>(c)] * r; });
    return a * visible(nm) + (1 - a) * bands;
  };
  return WavelengthSampler(minNm, maxNm, density, h);
}

double WavelengthSampler::wavelength(double u) const {
  const double x = std::clamp(u, 0.0, 1.0) * kSegments;
  const int j = cellIndex(x, kSegments);
  return knotNm_[j] + (x - j) * (knotNm_[j + 1] - knotNm_[j]);
}

double WavelengthSampler::pdf(double nm) const {
  if (nm < min_ || nm > max_) return 0.0;
  const int j =
      static_cast<int>(std::upper_bound(knotNm_.begin(), knotNm_.end(), nm) - knotNm_.begin()) - 1;
  return segmentPdf_[std::clamp(j, 0, kSegments - 1)];
}

SampledWavelengths WavelengthSampler::sample(float u) const {
  const float scaled = u * static_cast<float>(kLanes);
  const float stratum = std::min(std::floor(scaled), static_cast<float>(kLanes - 1));
  return sample(scaled - stratum, stratum / static_cast<float>(kLanes));
}

SampledWavelengths WavelengthSampler::sample(float offset, float heroStratum) const {
  SampledWavelengths w;
  const int hero = cellIndex(heroStratum * static_cast<float>(kLanes), kLanes);
  const float within = std::clamp(offset, 0.0f, 0x1.fffffep-1f);
  for (int i = 0; i < kLanes; ++i) {
    int stratum = hero + i;
    if (stratum >= kLanes) stratum -= kLanes;
    // Segment index and position within it, in double: (stratum + within) / kLanes * kSegments.
    const double x =
        (static_cast<double>(stratum) + within) * (static_cast<double>(kSegments) / kLanes);
    const int j = cellIndex(x, kSegments);
    const double f = x - j;
    w.lambda[i] = static_cast<float>(knotNm_[j] + f * (knotNm_[j + 1] - knotNm_[j]));
    w.pdf[i] = segmentPdf_[j];
  }
  return w;
}

} // namespace nx
