#pragma once
// Numbers from numpy arrays, taken as they are: real numbers their storage keeps (no complex
// part dropped, no 1e300 turned into inf or 1e-50 into 0 in float32, no -1 turned into
// 4294967295 in uint32), the first offending value named by its pixel.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vector>

namespace nxpy {

namespace py = pybind11;

/// numpy.asarray(value), refused (TypeError naming `param`) unless it holds real numbers
/// (ints or floats: not complex, bool, str or object).
py::array realArray(const py::handle& value, const char* param);

/// A numpy-convertible array of shape (h, w, depth) (or (h, w) when depth is 0) copied into a
/// pixel-interleaved vector of T. Every value must be a real number that T holds as it is:
/// finite, within [lo, hi], whole for an integer T, and for a float T not so small that it
/// would be stored as 0. Errors name `param`, the value and its row and column.
template <typename T>
std::vector<T> pixelsArgument(const py::handle& value, const char* param, py::ssize_t h,
                              py::ssize_t w, py::ssize_t depth, double lo, double hi);

} // namespace nxpy
