#pragma once
// Image.relight: a relightable render (render(..., relightable=True)) under new emission
// spectra of its light groups.

#include <pybind11/pybind11.h>

namespace nxpy {

/// Adds Image.relight and Image.relight_groups to the module's Image class.
void bindRelight(pybind11::module_& m);

} // namespace nxpy
