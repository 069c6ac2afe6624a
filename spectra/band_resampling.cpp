#include "spectra/band_resampling.h"

#include <cmath>

#include "core/error.h"

namespace nx {

BandResampling BandResampling::identity(int bands) {
  BandResampling r;
  r.inputs_ = r.outputs_ = bands;
  r.identity_ = true;
  r.w_.assign(static_cast<size_t>(bands) * bands, 0.0);
  for (int i = 0; i < bands; ++i) r.w_[static_cast<size_t>(i) * bands + i] = 1.0;
  return r;
}

BandResampling BandResampling::through(const std::vector<double>& c, const Sensor& capture,
                                       const std::string& where) {
  const int n = static_cast<int>(c.size());
  if (n == 0) throw Error(where + ": expected render bands to resample, found none");
  BandResampling r;
  r.inputs_ = n;
  r.outputs_ = capture.count();
  r.w_.assign(static_cast<size_t>(r.outputs_) * n, 0.0);
  const double lo = std::min(c.front(), capture.minNm()) - 1,
               hi = std::max(c.back(), capture.maxNm()) + 1;
  // Coverage: the share of each capture channel's response within the render's centroids.
  const Spectrum inside(TabulatedSpectrum{{c.front(), c.back()}, {1.0, 1.0}});
  for (int i = 0; i < r.outputs_; ++i) {
    const double share = n == 1 ? 0.0 : capture.average(inside, i);
    if (n > 1 && share < 0.99)
      throw Error(where + ": capture band " + std::to_string(i + 1) + " (centroid " +
                  numberText(capture.centroid(i)) + " nm, fwhm " + numberText(capture.fwhm(i)) +
                  " nm) lies beyond the render's bands (" + numberText(c.front()) + "-" +
                  numberText(c.back()) + " nm): " + numberText(std::round(share * 1000) / 10) +
                  "% of its response is covered, expected at least 99%");
  }
  for (int j = 0; j < n; ++j) {
    // hat_j: 1 at c_j, 0 at its neighbours; the end hats held out to the responses' ends.
    TabulatedSpectrum hat;
    if (j == 0)
      hat.nm.push_back(lo), hat.value.push_back(1.0);
    else
      hat.nm.push_back(c[static_cast<size_t>(j) - 1]), hat.value.push_back(0.0);
    hat.nm.push_back(c[static_cast<size_t>(j)]);
    hat.value.push_back(1.0);
    if (j == n - 1)
      hat.nm.push_back(hi), hat.value.push_back(1.0);
    else
      hat.nm.push_back(c[static_cast<size_t>(j) + 1]), hat.value.push_back(0.0);
    const Spectrum s(std::move(hat));
    for (int i = 0; i < r.outputs_; ++i)
      r.w_[static_cast<size_t>(i) * n + j] = capture.average(s, i);
  }
  return r;
}

void BandResampling::applyWeights(const float* in, float* out, bool squared) const {
  if (identity_) {
    for (int i = 0; i < inputs_; ++i) out[i] = in[i];
    return;
  }
  for (int i = 0; i < outputs_; ++i) {
    double sum = 0;
    const double* w = &w_[static_cast<size_t>(i) * inputs_];
    for (int j = 0; j < inputs_; ++j)
      if (w[j] != 0) sum += (squared ? w[j] * w[j] : w[j]) * in[j];
    out[i] = static_cast<float>(sum);
  }
}

void BandResampling::apply(const float* in, float* out) const {
  applyWeights(in, out, false);
}

void BandResampling::applyToVariance(const float* in, float* out) const {
  applyWeights(in, out, true);
}

} // namespace nx
