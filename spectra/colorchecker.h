#pragma once
// The ColorChecker Classic's 24 patches as measured reflectance spectra (Ohta 1997; the data
// file spectra/data/colorchecker_ohta.csv names the source).

#include <optional>
#include <string>
#include <vector>

#include "spectra/spectrum.h"

namespace nx {

/// Columns and rows of the chart.
inline constexpr int kColorCheckerColumns = 6, kColorCheckerRows = 4;

/// The patch names in chart order (row by row from the top left: dark_skin ... black_2).
const std::vector<std::string>& colorCheckerPatchNames();

/// The reflectance of patch `index` (0-23, chart order), tabulated every 10 nm over 380-780 nm.
const Spectrum& colorCheckerPatch(int index);

/// The reflectance of a patch by name ("dark_skin", "neutral_6.5", ...), or nothing.
std::optional<Spectrum> colorCheckerPatch(const std::string& name);

} // namespace nx
