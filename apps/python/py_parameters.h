#pragma once
// Scene parameters as Python values, by their declared type (core/params/parameter_set.h): one
// conversion each way per type, so every parameter of the scene format is readable and
// settable from Python without a binding of its own.

#include <pybind11/pybind11.h>

#include <string>

#include "core/params/parameter_set.h"

namespace nxpy {

namespace py = pybind11;

/// A parameter's value as Python sees it: float, (r, g, b, a), a spectrum (float, name, or
/// (wavelengths, values)), an ior (float, a glass name, ("cauchy" | "sellmeier", coefficients)),
/// a coating (thickness_nm, ior), a str.
py::object parameterToPython(const nx::ParamValue& v);

/// A Python value for the parameter `spec` checked as the scene loader checks it (types,
/// ranges); errors are ValueError / TypeError naming `param`. `loc` is what later errors
/// about it name.
nx::ParamValue parameterFromPython(const nx::ParamSpec& spec, const py::handle& value,
                                   const std::string& param, const nx::SourceLocation& loc);

/// A spectrum from Python: a number >= 0, a name, or (wavelengths_nm, values) (sequences or
/// numpy arrays).
nx::SpectrumDesc spectrumFromPython(const py::handle& value, const std::string& param,
                                    const nx::SourceLocation& loc);

/// A spectrum as Python sees it (see parameterToPython).
py::object spectrumToPython(const nx::SpectrumDesc& s);

/// Rows of `columns` numbers from an (N, columns) array: float32 reals (finite) or uint32
/// indices (whole, in [0, 2^32)); ValueError naming `param` and the first offending entry.
nx::ArrayDesc arrayFromPython(const py::handle& value, bool indices, uint32_t columns,
                              const std::string& param);

/// A number in `r`, or ValueError "param: expected <what> in [lo, hi], found v".
double rangedArgument(const py::handle& value, const std::string& param,
                      const nx::ParameterRange& r);

} // namespace nxpy
