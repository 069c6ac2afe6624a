#pragma once
// Measured complex refractive indices n + i k of metals, for conductors: gold, silver and copper
// tabulated by Johnson & Christy (1972; spectra/data/metals_johnson_christy_1972.csv), and
// aluminium from the Lorentz-Drude model of Rakic et al. (1998).

#include <optional>
#include <string>
#include <vector>

#include "spectra/spectrum.h"

namespace nx {

/// A metal's refractive index: real part eta and extinction coefficient k over wavelength.
struct MetalIndex {
  Spectrum eta; ///< n(lambda)
  Spectrum k;   ///< k(lambda)
};

/// The built-in metal names: gold, silver, copper, aluminium.
const std::vector<std::string>& metalNames();

/// A built-in metal's index by name, or std::nullopt. Gold, silver and copper interpolate
/// Johnson & Christy's table linearly in wavelength (188-1937 nm) and hold its ends; aluminium
/// is the Lorentz-Drude model evaluated every 5 nm over 200-2000 nm.
std::optional<MetalIndex> namedMetal(const std::string& name);

/// Aluminium's n + i k at a wavelength from the Lorentz-Drude model of A. D. Rakic, A. B.
/// Djurisic, J. M. Elazar and M. L. Majewski, "Optical properties of metallic films for
/// vertical-cavity optoelectronic devices", Applied Optics 37(22), 5271-5283 (1998), Table 1.
void aluminiumIndex(double nm, double& n, double& k);

} // namespace nx
