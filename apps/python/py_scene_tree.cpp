#include "apps/python/py_scene_tree.h"

#include <pybind11/numpy.h>

#include <cmath>

#include "apps/python/py_arguments.h"
#include "apps/python/py_arrays.h"

namespace nxpy {

namespace {

// How deep a scene's values nest at most: the scene, a list of objects, an object, a parameter
// such as a dye's spectra, a spectrum and its [nm, value] pairs, with room to spare. Deeper
// values (or a dict or list that contains itself) are refused before the recursion could
// overflow the stack.
constexpr int kMaxTreeDepth = 16;

// A Python number as a double; ValueError for one beyond double's range (an int of 400 digits).
double numberOf(const py::handle& value, const std::string& path) {
  const double v = PyFloat_AsDouble(value.ptr());
  if (v == -1.0 && PyErr_Occurred()) {
    PyErr_Clear();
    throw py::value_error(path + ": expected a finite number, found " + shortValueText(value));
  }
  return v;
}

nx::SceneTree treeAt(const py::handle& value, const std::string& path, int depth);

} // namespace

nx::SceneTree treeFromPython(const py::handle& value, const std::string& path) {
  return treeAt(value, path, 0);
}

namespace {

nx::SceneTree treeAt(const py::handle& value, const std::string& path, int depth) {
  if (depth > kMaxTreeDepth)
    throw py::value_error((path.empty() ? std::string("the value") : path) +
                          ": expected values nested at most " + std::to_string(kMaxTreeDepth) +
                          " levels deep (as a scene's are), found deeper nesting (a list or "
                          "dict that contains itself?)");
  if (value.is_none()) return {};
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) {
    const double v = numberOf(value, path);
    if (!std::isfinite(v))
      throw py::value_error(path + ": expected a finite number, found " +
                            py::repr(value).cast<std::string>());
    return v;
  }
  if (py::isinstance<py::dict>(value)) {
    nx::SceneTree::Dict d;
    for (const auto& [k, v] : value.cast<py::dict>()) {
      if (!py::isinstance<py::str>(k))
        throw py::type_error(path + ": expected string keys, found " + typeName(k));
      const std::string key = k.cast<std::string>();
      d.emplace_back(key, treeAt(v, path.empty() ? key : path + "." + key, depth + 1));
    }
    return d;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    nx::SceneTree::List l;
    size_t i = 0;
    for (const py::handle& v : value)
      l.push_back(treeAt(v, path + "[" + std::to_string(i++) + "]", depth + 1));
    return l;
  }
  if (py::hasattr(value, "__array__") || py::isinstance<py::array>(value)) {
    const py::array a = realArray(value, path.c_str());
    if (a.ndim() > 2)
      throw py::value_error(path + ": expected an array of 1 or 2 dimensions, found " +
                            std::to_string(a.ndim()));
    nx::SceneTree::Array out;
    const std::string kind = py::str(a.attr("dtype").attr("kind"));
    out.kind = kind != "f"                 ? nx::SceneTree::Array::Kind::Integer
               : a.dtype().itemsize() == 4 ? nx::SceneTree::Array::Kind::Float32
                                           : nx::SceneTree::Array::Kind::Float64;
    out.rows = a.ndim() == 0 ? 1 : static_cast<size_t>(a.shape(0));
    out.columns = a.ndim() == 2 ? static_cast<size_t>(a.shape(1)) : 0;
    const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    out.values.assign(d.data(), d.data() + d.size());
    for (size_t i = 0; i < out.values.size(); ++i)
      if (!std::isfinite(out.values[i]))
        throw py::value_error(path + ": expected finite numbers, found " +
                              py::str(py::float_(out.values[i])).cast<std::string>() +
                              " (element " + std::to_string(i) + ")");
    return out;
  }
  throw py::type_error(path + ": expected a number, a string, a list, a dict or an array, found " +
                       typeName(value));
}

} // namespace

py::object treeToPython(const nx::SceneTree& tree) {
  if (tree.as<std::monostate>()) return py::none();
  if (const bool* b = tree.as<bool>()) return py::bool_(*b);
  if (const double* d = tree.as<double>()) return py::float_(*d);
  if (const std::string* s = tree.as<std::string>()) return py::str(*s);
  if (const auto* a = tree.as<nx::SceneTree::Array>()) {
    std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(a->rows)};
    if (a->columns) shape.push_back(static_cast<py::ssize_t>(a->columns));
    if (a->kind == nx::SceneTree::Array::Kind::Float32) {
      py::array_t<float> out(shape);
      std::copy(a->values.begin(), a->values.end(), out.mutable_data());
      return out;
    }
    if (a->kind == nx::SceneTree::Array::Kind::Integer) {
      py::array_t<uint32_t> out(shape);
      for (size_t i = 0; i < a->values.size(); ++i)
        out.mutable_data()[i] = static_cast<uint32_t>(a->values[i]);
      return out;
    }
    py::array_t<double> out(shape);
    std::copy(a->values.begin(), a->values.end(), out.mutable_data());
    return out;
  }
  if (const auto* l = tree.as<nx::SceneTree::List>()) {
    py::list out;
    for (const nx::SceneTree& x : *l) out.append(treeToPython(x));
    return out;
  }
  py::dict out;
  for (const auto& [k, v] : *tree.as<nx::SceneTree::Dict>()) out[py::str(k)] = treeToPython(v);
  return out;
}

} // namespace nxpy
