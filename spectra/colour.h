#pragma once
// Spectrum -> XYZ -> linear sRGB (D65), the sRGB transfer function, CIELAB and CIEDE2000.

#include <array>

#include "core/matrix3.h"
#include "spectra/cie.h"
#include "spectra/spectrum.h"

namespace nx {

/// A linear or encoded RGB triple.
struct Rgb {
  double r = 0, g = 0, b = 0;
};

/// CIELAB coordinates.
struct Lab {
  double l = 0, a = 0, b = 0;
};

/// XYZ of a spectral radiance, normalised so that a flat spectrum of 1 has Y = 1
/// (1 nm sum over 360-830 nm divided by the integral of y-bar).
Xyz spectrumToXyz(const Spectrum& s);

/// XYZ of a reflectance under an illuminant, normalised so that a perfect white has Y = 1.
Xyz reflectanceToXyz(const Spectrum& reflectance, const Spectrum& illuminant);

/// The XYZ -> RGB matrix of an RGB space given its primaries' and white's chromaticities
/// (SMPTE RP 177 derivation).
Matrix3 rgbToXyzMatrix(const std::array<double, 8>& xyPrimariesAndWhite);

/// XYZ -> linear sRGB (ITU-R BT.709 primaries, D65 white).
Rgb xyzToLinearSrgb(const Xyz& c);
/// Linear sRGB -> XYZ.
Xyz linearSrgbToXyz(const Rgb& c);

/// The sRGB transfer function (IEC 61966-2-1) from linear to encoded, for one channel.
double srgbEncode(double linear);
/// The inverse sRGB transfer function, encoded to linear.
double srgbDecode(double encoded);

/// XYZ of the D65 white point with Y = 1 (x = 0.3127, y = 0.3290).
Xyz d65WhiteXyz();

/// CIELAB of c relative to the white point `white`.
Lab xyzToLab(const Xyz& c, const Xyz& white);

/// The CIEDE2000 colour difference (Sharma, Wu & Dalal 2005 formulation).
double deltaE2000(const Lab& a, const Lab& b);

} // namespace nx
