#pragma once
// The output bands of a spectral image: uniform bands given by centre and width.

#include <string>
#include <vector>

#include "spectra/spectrum.h"

namespace nx {

/// Uniform spectral bands: centres start, start+step, ..., end; each `step` nm wide.
struct SpectralBands {
  double startNm = 400, endNm = 700, stepNm = 10;

  /// The default: 31 bands centred 400..700 nm, 10 nm wide (CAVE/KAIST-style cameras).
  static SpectralBands defaults() { return {}; }
  /// Parses "START:END:STEP" (nm); errors say what was expected and what was found.
  static SpectralBands parse(const std::string& text);

  /// Number of bands.
  int count() const;
  /// Centre of band i (nm).
  double centre(int i) const { return startNm + i * stepNm; }
  /// Lower edge of band i (nm).
  double lower(int i) const { return centre(i) - 0.5 * stepNm; }
  /// Upper edge of band i (nm).
  double upper(int i) const { return centre(i) + 0.5 * stepNm; }
  /// Index of the band containing nm, or -1 (a shared edge belongs to the upper band).
  int bandOf(double nm) const;
  /// "START:END:STEP" as parse() reads it.
  std::string toString() const;
};

} // namespace nx
