#pragma once
// Python arguments to C++ values: each conversion names the parameter in its TypeError or
// ValueError, so a wrong call says which argument was wrong and what was expected.

#include <pybind11/pybind11.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace nxpy {

namespace py = pybind11;

/// A file name: str or os.PathLike (TypeError naming `param` otherwise).
std::string pathArgument(const py::handle& value, const char* param);
/// A str (TypeError naming `param` otherwise).
std::string stringArgument(const py::handle& value, const char* param);
/// An int (not a bool or float) in [lo, hi] (TypeError / ValueError naming `param`).
long long integerArgument(const py::handle& value, const char* param, long long lo, long long hi);
/// A real number (int or float, not bool), finite, in [lo, hi].
double numberArgument(const py::handle& value, const char* param, double lo, double hi);
/// True for a list, tuple or array read by position (not text, not a mapping such as a dict).
bool isSequence(const py::handle& value);

/// A sequence of exactly n real numbers (finite).
std::vector<double> numbersArgument(const py::handle& value, const char* param, size_t n);
/// A sequence of at least `minCount` finite real numbers.
std::vector<double> numberListArgument(const py::handle& value, const char* param, size_t minCount);
/// A sequence of exactly n ints.
std::vector<long long> integersArgument(const py::handle& value, const char* param, size_t n);
/// Python's name of a value's type ("int", "NoneType").
std::string typeName(const py::handle& value);
/// A value's str() for a message, a number of over 40 digits shortened to its first 20 and its
/// length ("12345678901234567890... (401 digits)").
std::string shortValueText(const py::handle& value);

} // namespace nxpy
