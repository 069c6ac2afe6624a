#pragma once
// The exact range of a spectrum's values over a wavelength interval, for validating scenes
// over every wavelength that can be traced (not only at whole nanometres).

#include <string>

#include "spectra/spectrum.h"

namespace nx {

/// Smallest and largest value of a spectrum over an interval and where they occur.
struct SpectrumExtremes {
  double min = 0, minNm = 0; ///< smallest value and a wavelength where it is taken
  double max = 0, maxNm = 0; ///< largest value and a wavelength where it is taken
};

/// The extremes of s over [loNm, hiNm] (loNm <= hiNm). Exact for constant, tabulated and
/// dense (piecewise-linear: every knot inside the interval and both ends are visited, so a
/// spike between whole nanometres is found), Gaussian, black-body and sigmoid-polynomial
/// spectra (their shape puts the extremes at the ends or at a known point); for skew-Cauchy
/// spectra the minimum is exact (they are never negative) and the maximum is found by a
/// sampled search refined to 1e-6 nm. A non-finite value anywhere makes both extremes NaN.
SpectrumExtremes spectrumExtremes(const Spectrum& s, double loNm, double hiNm);

/// The mean of s over [loNm, hiNm] (loNm < hiNm): exact for constant, tabulated and dense
/// spectra (piecewise linear between their knots, zero or held beyond their ends), the
/// trapezoidal rule on 0.05 nm steps for the analytic kinds. A line narrower than the interval
/// counts with its integral (sampling at the interval's centre would miss it or magnify it).
double spectrumMean(const Spectrum& s, double loNm, double hiNm);

/// "" for an emission within [0, kMaxEmission] at every traceable wavelength (300-1100 nm,
/// exactly), else "expected an emission within [0, 1e12] ..., found X at Y nm": the one check
/// of emitted spectra (scenes, relighting).
std::string emissionProblem(const Spectrum& s);

} // namespace nx
