#pragma once
// Smooth reflectance spectra for RGB colours (Jakob & Hanika, "A Low-Dimensional Function
// Space for Efficient Spectral Upsampling", EGSR 2019).

#include "spectra/colour.h"
#include "spectra/spectrum.h"

namespace nx {

/// A smooth reflectance spectrum in [0, 1] whose colour under D65 is the given linear sRGB
/// colour (each channel in [0, 1]): the sigmoid-polynomial coefficients interpolated in the
/// built-in table (srgbSigmoidTable(), fitted at build time). Black and white give constant
/// spectra.
Spectrum upsampleSrgbReflectance(const Rgb& linearSrgb);

/// An emission spectrum whose colour is the given linear sRGB colour (any non-negative
/// channels): max(c) * upsampled(c / max(c)) * D65 normalised to luminance 1, so that RGB
/// (1, 1, 1) is D65 with Y = 1 and the preview of the light shows exactly c.
Spectrum upsampleSrgbIlluminant(const Rgb& linearSrgb);

/// Colour of a reflectance spectrum under D65, as linear sRGB.
Rgb reflectanceToLinearSrgb(const Spectrum& reflectance);

} // namespace nx
