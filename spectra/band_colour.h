#pragma once
// Colour of band values: the bands read as a spectrum linear between their wavelengths (zero
// beyond the outer ones), integrated against the CIE 1931 functions. For images that come
// without their own XYZ and RGB (foreign spectral EXRs, arrays handed in from Python).

#include <array>
#include <vector>

#include "spectra/colour.h"
#include "spectra/sensor.h"

namespace nx {

/// XYZ as a weighted sum of band values: xyz = sum_b weight[b] * value[b].
class BandColour {
public:
  /// The weights for bands at these wavelengths (nm, strictly increasing).
  explicit BandColour(const std::vector<double>& wavelengthNm);
  /// XYZ of one pixel's band values (count() of them).
  Xyz xyz(const float* values) const;
  /// Fills xyz[pixel][3] and linear sRGB rgb[pixel][3] (negatives clamped to 0) of
  /// values[pixel][count()].
  void fill(const std::vector<float>& values, std::vector<float>& xyzOut,
            std::vector<float>& rgbOut) const;
  /// Number of bands.
  int count() const { return static_cast<int>(weight_.size()); }

private:
  std::vector<std::array<double, 3>> weight_;
};

/// The sensor of bands named only by their wavelengths: uniform boxes START:END:STEP when
/// they are evenly spaced (within 1e-6 nm), else Gaussian channels centred there with the
/// local spacing as FWHM. `where` names the source in errors.
Sensor sensorAtWavelengths(const std::vector<double>& wavelengthNm, const std::string& where);

} // namespace nx
