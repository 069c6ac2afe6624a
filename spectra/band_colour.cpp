// Colour of band values; sensors named by wavelengths alone.

#include "spectra/band_colour.h"
#include "core/number_text.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace nx {

BandColour::BandColour(const std::vector<double>& wavelengthNm) {
  // The spectrum is linear in the band values, so its XYZ is sum_b value_b * XYZ(hat_b) with
  // hat_b the piecewise-linear spectrum that is 1 at band b and 0 at the others.
  const size_t n = wavelengthNm.size();
  for (size_t b = 1; b < n; ++b)
    if (!(wavelengthNm[b] > wavelengthNm[b - 1]))
      throw Error("band colour: expected increasing wavelengths");
  weight_.resize(n);
  for (size_t b = 0; b < n; ++b) {
    if (n == 1) {
      weight_[b] = {0, 0, 0}; // a single band has no spectral extent
      break;
    }
    std::vector<double> v(n, 0.0);
    v[b] = 1;
    const Xyz c = spectrumToXyz(Spectrum(TabulatedSpectrum{wavelengthNm, v, false}));
    weight_[b] = {c.x, c.y, c.z};
  }
}

Xyz BandColour::xyz(const float* values) const {
  double x = 0, y = 0, z = 0;
  for (size_t b = 0; b < weight_.size(); ++b) {
    x += weight_[b][0] * values[b];
    y += weight_[b][1] * values[b];
    z += weight_[b][2] * values[b];
  }
  return {x, y, z};
}

void BandColour::fill(const std::vector<float>& values, std::vector<float>& xyzOut,
                      std::vector<float>& rgbOut) const {
  const size_t nb = weight_.size(), pixels = nb ? values.size() / nb : 0;
  xyzOut.assign(pixels * 3, 0.0f);
  rgbOut.assign(pixels * 3, 0.0f);
  for (size_t p = 0; p < pixels; ++p) {
    const Xyz c = xyz(values.data() + p * nb);
    const Rgb r = xyzToLinearSrgb(c);
    const double xyz3[3] = {c.x, c.y, c.z}, rgb3[3] = {r.r, r.g, r.b};
    for (int k = 0; k < 3; ++k) {
      xyzOut[p * 3 + k] = static_cast<float>(xyz3[k]);
      rgbOut[p * 3 + k] = static_cast<float>(std::max(0.0, rgb3[k]));
    }
  }
}

Sensor sensorAtWavelengths(const std::vector<double>& nm, const std::string& where) {
  if (nm.empty()) throw Error(where + ": expected at least one band, found none");
  for (size_t i = 1; i < nm.size(); ++i)
    if (!(nm[i] > nm[i - 1]))
      throw Error(where + ": expected increasing band wavelengths, found " +
                  std::to_string(nm[i - 1]) + " before " + std::to_string(nm[i]));
  if (nm.size() == 1) return Sensor::gaussian(nm, {10.0}, where);
  const double step = (nm.back() - nm.front()) / static_cast<double>(nm.size() - 1);
  bool uniform = true;
  for (size_t i = 0; i < nm.size(); ++i)
    uniform = uniform && std::abs(nm[i] - (nm.front() + step * static_cast<double>(i))) < 1e-6;
  if (uniform) {
    const std::string text = generalText(nm.front(), 17) + ":" + generalText(nm.back(), 17) + ":" +
                             generalText(step, 17);
    const Sensor s = Sensor::parse(text, where);
    if (s.count() == static_cast<int>(nm.size())) return s;
  }
  std::vector<double> fwhm(nm.size());
  for (size_t i = 0; i < nm.size(); ++i) {
    const double left = i > 0 ? nm[i] - nm[i - 1] : nm[i + 1] - nm[i];
    const double right = i + 1 < nm.size() ? nm[i + 1] - nm[i] : left;
    fwhm[i] = 0.5 * (left + right);
  }
  return Sensor::gaussian(nm, fwhm, where);
}

} // namespace nx
