#include "apps/python/py_arrays.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <type_traits>

#include "apps/python/py_arguments.h"
#include "core/error.h"

namespace nxpy {

py::array realArray(const py::handle& value, const char* param) {
  py::object asArray;
  try {
    asArray = py::module_::import("numpy").attr("asarray")(value);
  } catch (const py::error_already_set&) {
    throw py::type_error(std::string(param) + ": expected an array of numbers, found " +
                         typeName(value));
  }
  const std::string kind = py::str(asArray.attr("dtype").attr("kind"));
  if (kind == "c")
    throw py::type_error(std::string(param) +
                         ": expected an array of real numbers, found complex numbers");
  if (kind != "f" && kind != "i" && kind != "u")
    throw py::type_error(std::string(param) + ": expected an array of numbers, found " +
                         typeName(value));
  return asArray.cast<py::array>();
}

template <typename T>
std::vector<T> pixelsArgument(const py::handle& value, const char* param, py::ssize_t h,
                              py::ssize_t w, py::ssize_t depth, double lo, double hi) {
  const py::array asArray = realArray(value, param);
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(asArray);
  } catch (const py::error_already_set&) {
  }
  if (!a) {
    PyErr_Clear();
    throw py::type_error(std::string(param) + ": expected an array of numbers, found " +
                         typeName(value));
  }
  const bool shapeOk =
      depth == 0 ? a.ndim() == 2 && a.shape(0) == h && a.shape(1) == w
                 : a.ndim() == 3 && a.shape(0) == h && a.shape(1) == w && a.shape(2) == depth;
  if (!shapeOk) {
    std::string found = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i)
      found += (i ? ", " : "") + std::to_string(a.shape(i));
    found += a.ndim() == 1 ? ",)" : ")";
    throw py::value_error(
        std::string(param) + ": expected shape (" + std::to_string(h) + ", " + std::to_string(w) +
        (depth ? ", " + std::to_string(depth) : std::string()) + "), found " + found);
  }
  std::vector<T> out(static_cast<size_t>(a.size()));
  const double* v = a.data();
  for (size_t i = 0; i < out.size(); ++i) {
    const bool whole = !std::is_integral_v<T> || v[i] == std::floor(v[i]);
    // A float keeps a non-zero value unless it is below its smallest (1e-50 became 0).
    const bool kept = std::is_integral_v<T> || v[i] == 0 || static_cast<T>(v[i]) != 0;
    if (!(std::isfinite(v[i]) && v[i] >= lo && v[i] <= hi && whole && kept)) {
      const size_t perPixel = depth ? static_cast<size_t>(depth) : 1;
      const size_t p = i / perPixel;
      const std::string at = " at row " + std::to_string(p / static_cast<size_t>(w)) + ", column " +
                             std::to_string(p % static_cast<size_t>(w));
      if (!kept)
        throw py::value_error(std::string(param) + ": expected 0 or a magnitude of at least " +
                              "1.4e-45 (what float32 stores), found " + nx::numberText(v[i]) + at);
      throw py::value_error(std::string(param) + ": expected " +
                            (std::is_integral_v<T> ? "whole numbers" : "finite numbers") + " in [" +
                            nx::exactNumberText(lo) + ", " + nx::exactNumberText(hi) + "], found " +
                            nx::numberText(v[i]) + at);
    }
    out[i] = static_cast<T>(v[i]);
  }
  return out;
}

template std::vector<float> pixelsArgument<float>(const py::handle&, const char*, py::ssize_t,
                                                  py::ssize_t, py::ssize_t, double, double);
template std::vector<uint32_t> pixelsArgument<uint32_t>(const py::handle&, const char*, py::ssize_t,
                                                        py::ssize_t, py::ssize_t, double, double);

} // namespace nxpy
