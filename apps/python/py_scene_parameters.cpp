// Scene.parameters(), Scene.get(name), Scene.set(name, value): every parameter of the scene
// by a stable name (the names Scene.edits records), with its type, unit, range and meaning, as
// the library lists them (integrators/scene_params/scene_parameter_list.h). Values are read and
// set through the views' properties, so a value set by name is checked and recorded exactly as
// one set by attribute.

#include "apps/python/py_scene_parameters.h"

#include <pybind11/stl.h>

#include <variant>

#include <pybind11/numpy.h>

#include "core/error.h"
#include "core/hash.h"
#include "integrators/scene_params/parameter_numbers.h"
#include "integrators/scene_params/parameter_path.h"
#include "integrators/scene_params/scene_parameter_list.h"

namespace nxpy {
namespace {

// A name as steps for walking the views: (attribute, index) with the index as Python's (None,
// an int or a str); KeyError when the name is not of the form of parameter names.
struct Step {
  std::string attribute;
  py::object index;
};

std::vector<Step> steps(const std::string& name) {
  std::vector<nx::ParameterStep> parsed;
  try {
    parsed = nx::parameterSteps(name);
  } catch (const nx::Error& e) {
    throw py::key_error(e.what());
  }
  std::vector<Step> out;
  for (const nx::ParameterStep& s : parsed) {
    Step step{s.attribute, py::none()};
    if (const size_t* i = std::get_if<size_t>(&s.index)) step.index = py::int_(*i);
    if (const std::string* k = std::get_if<std::string>(&s.index)) step.index = py::str(*k);
    out.push_back(std::move(step));
  }
  return out;
}

// The canonical spelling of a name (materials["x"] -> materials['x']), checked to be one of
// the scene's parameters.
std::string knownName(const SceneState& s, const std::string& name) {
  try {
    return nx::sceneParameter(s.desc, name).name;
  } catch (const nx::Error& e) {
    throw py::key_error(e.what());
  }
}

// An object's material parameters are named after the object ("objects[1].reflectance", as
// errors and edits name them): the step goes through its material view.
py::object owner(const py::object& at, const std::string& attribute) {
  if (!py::hasattr(at, attribute.c_str()) && py::hasattr(at, "material"))
    return at.attr("material");
  return at;
}

// The object holding the last step, walking the views from the scene.
py::object holder(const py::object& scene, const std::vector<Step>& path) {
  py::object at = scene;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const py::object from = owner(at, path[i].attribute);
    at = from.attr(path[i].attribute.c_str());
    if (!path[i].index.is_none()) at = at[path[i].index];
    if (at.is_none())
      throw py::key_error("the scene has no " + path[i].attribute + " here any more");
  }
  return owner(at, path.back().attribute);
}

// A parameter's numbers as a numpy array of their shape: () for one number, (n,) for a colour
// or a table's values, (excitation, emission) for a matrix, (height, width[, bands]) for a
// concentration map or a texture.
py::array_t<double> numbersToPython(const nx::ParameterNumbers& n) {
  std::vector<py::ssize_t> shape;
  if (n.form == nx::ParameterNumbers::Form::List || n.form == nx::ParameterNumbers::Form::Table)
    shape = {static_cast<py::ssize_t>(n.values.size())};
  for (long d : n.shape) shape.push_back(d);
  py::array_t<double> a(shape);
  std::copy(n.values.begin(), n.values.end(), a.mutable_data());
  return a;
}

// Scene.numbers(name) and Scene.set_numbers(name, values): a parameter's numbers by name
// (integrators/scene_params/parameter_numbers.h), what nxrender.torch moves.
void bindParameterNumbers(const py::object& scene) {
  scene.attr("numbers") = py::cpp_function(
      [](const py::object& self, const std::string& name) {
        const PyScene& s = self.cast<const PyScene&>();
        return numbersToPython(nx::parameterNumbers(s.state->desc, knownName(*s.state, name)));
      },
      py::name("numbers"), py::is_method(scene), py::arg("name"),
      "The numbers of the parameter called `name` as a float64 array: () for a number, (n,) "
      "for a colour or a table's values (at its own wavelengths), (excitation, emission) for a "
      "measured matrix, (height, width) for a concentration map, (height, width, bands) for a "
      "texture (nxrender.Error: a parameter without numbers, e.g. a named spectrum)");
  scene.attr("set_numbers") = py::cpp_function(
      [](const py::object& self, const std::string& name, const py::object& values) {
        const PyScene& s = self.cast<const PyScene&>();
        const std::string known = knownName(*s.state, name);
        const py::array_t<double, py::array::c_style | py::array::forcecast> a =
            py::module_::import("numpy").attr("asarray")(values, "float64");
        const nx::ParameterNumbers before = nx::parameterNumbers(s.state->desc, known);
        const py::array_t<double> expected = numbersToPython(before);
        if (a.ndim() != expected.ndim() ||
            !std::equal(a.shape(), a.shape() + a.ndim(), expected.shape()))
          throw py::value_error(known + ": expected numbers of shape " +
                                py::repr(expected.attr("shape")).cast<std::string>() + ", found " +
                                py::repr(a.attr("shape")).cast<std::string>());
        if (!nx::setParameterNumbers(s.state->desc, known,
                                     std::span<const double>(a.data(), a.size())))
          throw py::value_error(known + ": a value outside what the parameter allows (its "
                                        "range; spectra not negative; reflectances, texels and "
                                        "concentrations within [0, 1])");
        s.state->record(known, a.size() <= 8 ? py::repr(a.attr("tolist")()).cast<std::string>()
                                             : "<numbers " + std::to_string(a.size()) + " digest " +
                                                   std::to_string(nx::fnv1a64(std::string_view(
                                                       reinterpret_cast<const char*>(a.data()),
                                                       a.size() * sizeof(double)))) +
                                                   ">");
      },
      py::name("set_numbers"), py::is_method(scene), py::arg("name"), py::arg("values"),
      "Sets the numbers of the parameter called `name` (the shape numbers() gives), each "
      "checked; its form stays (a table keeps its wavelengths and extrapolation); recorded");
}

} // namespace

void bindSceneParameters(py::module_& m) {
  py::object scene = m.attr("Scene");
  scene.attr("parameters") = py::cpp_function(
      [](const py::object& self) {
        const PyScene& s = self.cast<const PyScene&>();
        py::dict out;
        for (const nx::SceneParameterInfo& e : nx::sceneParameters(s.state->desc)) {
          py::dict d;
          const std::vector<Step> path = steps(e.name);
          const py::object at = holder(self, path);
          py::object value = at.attr(path.back().attribute.c_str());
          // A fluorescence is a view of its fields (listed as parameters of their own).
          if (e.type == nx::paramTypeName(nx::ParamType::Fluorescence) && !value.is_none())
            value = value.attr("matrix_file").is_none() && value.attr("matrix").is_none()
                        ? py::str("model")
                        : py::str("matrix");
          d["value"] = value;
          d["type"] = e.type;
          d["unit"] = e.unit;
          d["range"] = e.range ? py::object(py::make_tuple(e.range->lo, e.range->hi))
                               : py::object(py::none());
          d["default"] = e.defaultText.empty() ? py::object(py::none()) : py::str(e.defaultText);
          d["doc"] = e.doc;
          d["differentiable"] = e.differentiable;
          out[py::str(e.name)] = d;
        }
        return out;
      },
      py::name("parameters"), py::is_method(scene),
      "Every parameter of the scene by its stable name (the names Scene.edits records): a dict "
      "name -> {value, type, unit, range, default, doc, differentiable}. Material parameters a "
      "kind takes are "
      "listed whether given or not (value None: the kind's default).");
  scene.attr("get") = py::cpp_function(
      [](const py::object& self, const std::string& name) -> py::object {
        const PyScene& s = self.cast<const PyScene&>();
        const std::vector<Step> path = steps(knownName(*s.state, name));
        const py::object at = holder(self, path);
        return at.attr(path.back().attribute.c_str());
      },
      py::name("get"), py::is_method(scene), py::arg("name"),
      "The value of the parameter called `name` (see parameters())");
  scene.attr("set") = py::cpp_function(
      [](const py::object& self, const std::string& name, const py::object& value) {
        const PyScene& s = self.cast<const PyScene&>();
        const std::vector<Step> path = steps(knownName(*s.state, name));
        py::setattr(holder(self, path), path.back().attribute.c_str(), value);
      },
      py::name("set"), py::is_method(scene), py::arg("name"), py::arg("value"),
      "Sets the parameter called `name`, checked and recorded as the attribute's setter does "
      "(ValueError / TypeError naming it)");
  bindParameterNumbers(scene);
}

} // namespace nxpy
