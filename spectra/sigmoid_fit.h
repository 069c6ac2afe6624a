#pragma once
// Fitting the three coefficients of a sigmoid-polynomial reflectance to a colour (Jakob &
// Hanika, "A Low-Dimensional Function Space for Efficient Spectral Upsampling", EGSR 2019).

#include <array>

#include "spectra/colour.h"

namespace nx {

/// Coefficients (c0, c1, c2) of SigmoidPolynomialSpectrum.
using SigmoidCoefficients = std::array<double, 3>;

/// The coefficients of a constant reflectance z in (0, 1): c0 = c1 = 0 and S(c2) = z.
SigmoidCoefficients greySigmoidCoefficients(double z);

/// Coefficients whose spectrum has, under D65, the CIELAB colour of the given linear sRGB
/// colour (channels in [0, 1]): Levenberg-Marquardt on the CIELAB difference, started at
/// `start`. Converges when `start` is the solution of a nearby colour (the paper's
/// continuation); returns the best coefficients found.
SigmoidCoefficients fitSigmoidCoefficients(const Rgb& linearSrgb, SigmoidCoefficients start);

/// As fitSigmoidCoefficients, but walking in `steps` equal steps from `fromSrgb` (whose
/// solution is `from`) to the target, so that a distant colour is reached through near ones.
SigmoidCoefficients fitSigmoidCoefficientsFrom(const Rgb& linearSrgb, const Rgb& fromSrgb,
                                               SigmoidCoefficients from, int steps);

/// CIEDE2000 under D65 between the colour of the coefficients' spectrum and a linear sRGB
/// colour: the fit's error.
double sigmoidFitDeltaE(const SigmoidCoefficients& c, const Rgb& linearSrgb);

} // namespace nx
