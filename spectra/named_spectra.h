#pragma once
// The reflectance names of Niixtracer scene files.

#include <optional>
#include <string>

#include "spectra/spectrum.h"

namespace nx {

/// Reflectance by Niixtracer name: red orange yellow green blue purple uv are Gaussians
/// peaking (value 1) at 680 620 600 545 460 420 360 nm with sigma 34 nm; const = 1,
/// null = 0, gray = 0.5. Unknown names give std::nullopt.
std::optional<Spectrum> namedReflectance(const std::string& name);

/// Peak wavelength (nm) a Niixtracer colour name stands for in <absorption>: the reflectance
/// peaks, except uv at 370 nm (fluorescence spec). Unknown names give std::nullopt.
std::optional<double> namedAbsorptionPeak(const std::string& name);

} // namespace nx
