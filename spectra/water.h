#pragma once
// Pure water's absorption and scattering coefficients (Smith & Baker 1981; the data file
// spectra/data/water_smith_baker_1981.csv names the source), for media.

#include <optional>
#include <string>

#include "spectra/spectrum.h"

namespace nx {

/// A medium coefficient by name, per metre: "water:absorption" (a_w) or "water:scattering"
/// (b_m), tabulated every 10 nm over 200-800 nm and held constant beyond. Unknown names give
/// std::nullopt.
std::optional<Spectrum> namedMediumCoefficient(const std::string& name);

} // namespace nx
