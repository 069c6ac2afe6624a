// Python arguments to C++ values with errors naming the parameter.

#include "apps/python/py_arguments.h"

#include <cmath>
#include <limits>

namespace nxpy {

std::string shortValueText(const py::handle& value) {
  const std::string text = py::str(value).cast<std::string>();
  return text.size() > 40 ? text.substr(0, 20) + "... (" + std::to_string(text.size()) + " digits)"
                          : text;
}

std::string typeName(const py::handle& value) {
  return py::str(py::type::handle_of(value).attr("__name__"));
}

std::string pathArgument(const py::handle& value, const char* param) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__fspath__")) {
    const py::object p = value.attr("__fspath__")();
    if (py::isinstance<py::str>(p)) return p.cast<std::string>();
  }
  throw py::type_error(std::string(param) + ": expected a file name (str or os.PathLike), found " +
                       typeName(value));
}

std::string stringArgument(const py::handle& value, const char* param) {
  if (!py::isinstance<py::str>(value))
    throw py::type_error(std::string(param) + ": expected a str, found " + typeName(value));
  return value.cast<std::string>();
}

long long integerArgument(const py::handle& value, const char* param, long long lo, long long hi) {
  // int, or anything with __index__ (numpy integers), but not bool
  if (py::isinstance<py::bool_>(value) || !py::hasattr(value, "__index__"))
    throw py::type_error(std::string(param) + ": expected an int, found " + typeName(value));
  long long v = 0;
  try {
    v = value.attr("__index__")().cast<long long>();
  } catch (const py::cast_error&) { // beyond 64 bits
    throw py::value_error(std::string(param) + ": expected an int in [" + std::to_string(lo) +
                          ", " + std::to_string(hi) + "], found " + shortValueText(value));
  }
  if (v < lo || v > hi)
    throw py::value_error(std::string(param) + ": expected an int in [" + std::to_string(lo) +
                          ", " + std::to_string(hi) + "], found " + std::to_string(v));
  return v;
}

namespace {
double realNumber(const py::handle& value, const std::string& param) {
  // complex (Python's or numpy's) has a real part but is not a real number: refused, not cut
  if (typeName(value).find("complex") != std::string::npos)
    throw py::type_error(param + ": expected a real number, found " + typeName(value));
  if (py::isinstance<py::bool_>(value) ||
      !(py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value) ||
        py::hasattr(value, "__float__")))
    throw py::type_error(param + ": expected a number, found " + typeName(value));
  // An array of more than one value (a row of a 2-D array where a number belongs): numpy's
  // own "only size-1 arrays can be converted" would not name the argument.
  if (py::hasattr(value, "shape") && py::hasattr(value, "size") &&
      value.attr("size").cast<py::ssize_t>() != 1)
    throw py::type_error(param + ": expected a number, found an array of shape " +
                         py::str(value.attr("shape")).cast<std::string>());
  const double v = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
  if (!std::isfinite(v))
    throw py::value_error(param + ": expected a finite number, found " +
                          py::str(value).cast<std::string>());
  return v;
}
} // namespace

double numberArgument(const py::handle& value, const char* param, double lo, double hi) {
  const double v = realNumber(value, param);
  if (v < lo || v > hi)
    throw py::value_error(std::string(param) + ": expected a number in [" +
                          py::str(py::float_(lo)).cast<std::string>() + ", " +
                          py::str(py::float_(hi)).cast<std::string>() + "], found " +
                          py::str(py::float_(v)).cast<std::string>());
  return v;
}

bool isSequence(const py::handle& value) {
  // A list, a tuple or a numpy array: indexed by position. Text is not, and a mapping (a dict
  // has a length and items too) is read by its keys: a dict gave "KeyError: 0".
  if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) ||
      py::isinstance<py::dict>(value) || py::hasattr(value, "keys"))
    return false;
  return py::isinstance<py::sequence>(value) ||
         (py::hasattr(value, "__len__") && py::hasattr(value, "__getitem__"));
}

std::vector<double> numberListArgument(const py::handle& value, const char* param,
                                       size_t minCount) {
  if (!isSequence(value))
    throw py::type_error(std::string(param) + ": expected a sequence of numbers, found " +
                         typeName(value));
  std::vector<double> out;
  const size_t n = py::len(value);
  for (size_t i = 0; i < n; ++i)
    out.push_back(
        realNumber(value[py::int_(i)], std::string(param) + "[" + std::to_string(i) + "]"));
  if (out.size() < minCount)
    throw py::value_error(std::string(param) + ": expected at least " + std::to_string(minCount) +
                          " numbers, found " + std::to_string(out.size()));
  return out;
}

std::vector<double> numbersArgument(const py::handle& value, const char* param, size_t n) {
  const std::vector<double> v = numberListArgument(value, param, 0);
  if (v.size() != n)
    throw py::value_error(std::string(param) + ": expected " + std::to_string(n) +
                          " numbers, found " + std::to_string(v.size()));
  return v;
}

std::vector<long long> integersArgument(const py::handle& value, const char* param, size_t n) {
  if (!isSequence(value))
    throw py::type_error(std::string(param) + ": expected a sequence of " + std::to_string(n) +
                         " ints, found " + typeName(value));
  if (py::len(value) != n)
    throw py::value_error(std::string(param) + ": expected " + std::to_string(n) + " ints, found " +
                          std::to_string(py::len(value)));
  std::vector<long long> out;
  for (size_t i = 0; i < n; ++i) {
    const py::object item = value[py::int_(i)];
    // numpy integers are not int subclasses; accept anything with __index__
    if (py::isinstance<py::bool_>(item) || !py::hasattr(item, "__index__"))
      throw py::type_error(std::string(param) + "[" + std::to_string(i) +
                           "]: expected an int, found " + typeName(item));
    out.push_back(integerArgument(
        item, (std::string(param) + "[" + std::to_string(i) + "]").c_str(),
        std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max()));
  }
  return out;
}

} // namespace nxpy
