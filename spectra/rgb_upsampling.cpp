#include "spectra/rgb_upsampling.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "spectra/illuminants.h"
#include "spectra/sigmoid_table.h"

namespace nx {

Spectrum upsampleSrgbReflectance(const Rgb& rgb) {
  for (double v : {rgb.r, rgb.g, rgb.b})
    if (!(v >= 0.0 && v <= 1.0))
      throw Error("reflectance colour channels must lie in [0, 1], found " + std::to_string(v));
  if (rgb.r == rgb.g && rgb.g == rgb.b && (rgb.r == 0.0 || rgb.r == 1.0))
    return Spectrum(ConstantSpectrum{rgb.r});
  const SigmoidCoefficients c = srgbSigmoidTable().lookup(rgb);
  return Spectrum(SigmoidPolynomialSpectrum{c[0], c[1], c[2]});
}

Spectrum upsampleSrgbIlluminant(const Rgb& rgb) {
  for (double v : {rgb.r, rgb.g, rgb.b})
    if (!(v >= 0.0 && std::isfinite(v)))
      throw Error("emission colour channels must be finite and non-negative, found " +
                  std::to_string(v));
  const double m = std::max({rgb.r, rgb.g, rgb.b});
  if (m == 0) return Spectrum(ConstantSpectrum{0});
  const Spectrum shape = upsampleSrgbReflectance({rgb.r / m, rgb.g / m, rgb.b / m});
  const Spectrum d65 = *namedEmission("D65");
  std::vector<double> nm, v;
  for (int l = 300; l <= 830; ++l) {
    nm.push_back(l);
    v.push_back(m * shape(l) * d65(l));
  }
  return Spectrum(TabulatedSpectrum{std::move(nm), std::move(v)});
}

Rgb reflectanceToLinearSrgb(const Spectrum& reflectance) {
  static const Spectrum d65 = illuminantD(nominalDaylightCct(65));
  return xyzToLinearSrgb(reflectanceToXyz(reflectance, d65));
}

} // namespace nx
