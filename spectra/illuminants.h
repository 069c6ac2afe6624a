#pragma once
// CIE standard illuminants, black bodies, the black light, and their names.

#include <optional>
#include <string>

#include "spectra/spectrum.h"

namespace nx {

/// CIE standard illuminant A from its defining formula (relative, 100 at 560 nm), tabulated
/// every nm over the whole traced range (300-1100 nm).
Spectrum illuminantA();

/// CIE daylight at correlated colour temperature cct (4000-25000 K) from the S0/S1/S2 basis
/// (CIE 15 procedure, M1 and M2 rounded to three decimals), relative, 5 nm table 300-830 nm.
Spectrum illuminantD(double cct);

/// The CCT CIE uses for "D<nn>": nn * 100 * 1.4388 / 1.4380 (e.g. D65 -> 6503.6 K).
double nominalDaylightCct(int hundredsOfKelvin);

/// CIE fluorescent illuminant F1..F12 (tabulated, 5 nm, 380-780 nm).
Spectrum illuminantF(int index);

/// CIE illuminant E (equal energy), value 1.
Spectrum illuminantE();

/// The black light: a UV line near 368 nm and a weaker violet line at 404.7 nm (Gaussians of
/// sigma 10 nm and 4 nm, peak ratio 1 : 0.3), the shape described for Niixtracer's `bl`.
Spectrum blackLight();

/// Relative luminance Y of a spectrum, with a flat spectrum of 1 giving Y = 1.
double relativeLuminance(const Spectrum& s);

/// Looks up an emission/illuminant name and returns it normalised for use as emitted
/// radiance: CIE names (A, D50, D55, D65, D75, D<nn>, daylight:<K>, F1..F12, E),
/// blackbody:<K>, and the Niixtracer names bba bbd50 bbd55 bbd65 bbd75 (black bodies at
/// 2856 5003 5503 6504 7504 K) and bl. Every one is scaled to the luminance of a flat
/// spectrum of 1, except the black light (nearly invisible by design), which is scaled to
/// the radiance of a flat 1 integrated over 360-830 nm. Unknown names give std::nullopt;
/// known names with bad parameters throw nx::Error.
std::optional<Spectrum> namedEmission(const std::string& name);

} // namespace nx
