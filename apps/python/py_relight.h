#pragma once
// Image.relight: a relightable render (render(..., relightable=True)) under new emission
// spectra of its light groups.

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "integrators/relight_targets.h"

namespace nxpy {

/// A spectrum from a Python value: a CSV file name (two columns nm,value) or a built-in
/// emission name ('D65'), a pair (wavelengths, values) of a piecewise-linear table (0 outside),
/// or one number (flat); errors name `param`.
nx::TextSpectrum spectrumFromPython(const pybind11::handle& value, const std::string& param);

/// render()'s relight_for=: a spectrum or a list of them (for every light group), or a dict
/// {group: spectrum or list of spectra}; each checked as --relight-for checks its targets.
std::vector<nx::RelightTargetDesc> relightTargetsArgument(const pybind11::handle& value);

/// Adds Image.relight and Image.relight_groups to the module's Image class.
void bindRelight(pybind11::module_& m);

} // namespace nxpy
