// Slots and tangents of a differentiated render: each requested parameter's numbers are moved by
// a small step in copies of the scene (through scene.set, so every value is checked as any
// edit), the copies resolved, and the scene's data differenced (central differences, one-sided
// of second order at the end of a parameter's range).

#include "apps/python/py_gradients.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>

#include "apps/render_job.h"
#include "core/error.h"
#include "io/scene_desc.h"

namespace nxpy {
namespace {

// The last part of a name: "objects[1].fluorescence.stokes_nm" -> "stokes_nm".
std::string leafOf(const std::string& name) {
  const size_t dot = name.rfind('.');
  return dot == std::string::npos ? name : name.substr(dot + 1);
}

// A parameter's numbers as a flat list, and how to write a list back as its value: a number,
// the values of (wavelengths_nm, values), or a sequence of numbers (a colour).
struct Numbers {
  std::vector<double> values;
  bool indexed = false;
  py::object wavelengths; ///< a tabulated spectrum's, else None
  bool texture = false;   ///< a texture's texels (values in textureValues)
  py::object textureValues;
  /// A measured matrix's (excitation_nm, emission_nm): its cells are the numbers, row by row
  py::object excitation, emission;
  std::vector<long> shape; ///< the numbers' shape when not a flat list
  py::object valueOf(const std::vector<double>& v) const {
    if (!indexed) return py::float_(v[0]);
    py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
    std::copy(v.begin(), v.end(), a.mutable_data());
    if (!excitation.is_none())
      return py::make_tuple(excitation, emission,
                            a.attr("reshape")(py::make_tuple(shape[0], shape[1])));
    if (!wavelengths.is_none()) return py::make_tuple(wavelengths, a);
    return py::tuple(a.attr("tolist")());
  }
};

bool isNumber(const py::handle& v) {
  return !py::isinstance<py::bool_>(v) &&
         (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v));
}

Numbers numbersOf(const py::object& value, const std::string& name) {
  Numbers n;
  n.wavelengths = py::none();
  n.excitation = py::none();
  n.emission = py::none();
  if (isNumber(value)) {
    n.values = {value.cast<double>()};
    return n;
  }
  const py::object np = py::module_::import("numpy");
  auto floats = [&](const py::handle& h) {
    const py::array_t<double> a = np.attr("asarray")(h, "float64");
    if (a.ndim() != 1) throw py::value_error(name + ": not differentiable: expected numbers");
    return std::vector<double>(a.data(), a.data() + a.size());
  };
  if (py::isinstance<py::tuple>(value) && py::len(value) == 3) {
    // a measured matrix: (excitation_nm, emission_nm, values[excitation, emission])
    const py::tuple t = value.cast<py::tuple>();
    const py::array_t<double> v = np.attr("asarray")(t[2], "float64");
    if (v.ndim() == 2) {
      n.values.assign(v.data(), v.data() + v.size());
      n.indexed = true;
      n.excitation = t[0];
      n.emission = t[1];
      n.shape = {static_cast<long>(v.shape(0)), static_cast<long>(v.shape(1))};
      return n;
    }
  }
  if (py::isinstance<py::tuple>(value) && py::len(value) == 2 &&
      !isNumber(value.cast<py::tuple>()[0])) {
    // a tabulated spectrum: (wavelengths_nm, values), or a texture (values of 3 axes)
    const py::tuple t = value.cast<py::tuple>();
    const py::array v = np.attr("asarray")(t[1]);
    if (v.ndim() == 3) { // a texture: (height, width, bands)
      n.texture = true;
      n.indexed = true;
      n.wavelengths = np.attr("asarray")(t[0], "float64");
      n.textureValues = np.attr("asarray")(t[1], "float64");
      return n;
    }
    if (v.ndim() != 1) throw py::value_error(name + ": not differentiable: expected numbers");
    n.values = floats(t[1]);
    n.indexed = true;
    n.wavelengths = np.attr("asarray")(t[0], "float64");
    return n;
  }
  if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
    bool all = py::len(value) > 0;
    for (const py::handle h : value) all = all && isNumber(h);
    if (all) {
      n.values = floats(value);
      n.indexed = true;
      return n;
    }
  }
  std::string found = py::str(value);
  if (found.size() > 60) found = found.substr(0, 60) + "...";
  throw py::value_error(name +
                        ": not differentiable as given: expected a number, a tabulated "
                        "spectrum (wavelengths_nm, values) or a colour, found " +
                        found +
                        " (a named or built-in spectrum: set it as (wavelengths_nm, values) "
                        "first, or differentiate its scale)");
}

// The resolved scene of `scene` with its parameter `name` set to `value`; false when the
// value is refused (outside the parameter's range).
bool resolvedWith(const py::object& scene, const std::string& name, const py::object& value,
                  bool fluorescence, std::optional<nx::RenderScene>& out) {
  py::object copy = scene.attr("copy")();
  try {
    copy.attr("set")(name, value);
  } catch (py::error_already_set& e) {
    if (e.matches(PyExc_ValueError)) return false;
    throw;
  }
  nx::SceneDesc desc = sceneForRendering(*copy.cast<const PyScene&>().state);
  if (!fluorescence) nx::removeFluorescence(desc);
  py::gil_scoped_release release;
  out.emplace(nx::resolveRenderScene(desc));
  return true;
}

} // namespace

GradientRequest gradientRequest(const py::object& scene, const py::handle& names,
                                const nx::RenderScene& base, bool fluorescence) {
  if (py::isinstance<py::str>(names) || !py::hasattr(names, "__iter__"))
    throw py::type_error("gradients: expected a list of parameter names (scene.parameters()), "
                         "found " +
                         std::string(py::str(py::type::of(names).attr("__name__"))));
  GradientRequest r;
  r.tangents = nx::SceneTangents::sizedFor(base);
  const py::dict known = scene.attr("parameters")();
  for (const py::handle item : names) {
    if (!py::isinstance<py::str>(item)) throw py::type_error("gradients: expected parameter names");
    std::string name = item.cast<std::string>();
    std::replace(name.begin(), name.end(), '"', '\'');
    if (!known.contains(name))
      throw py::key_error("gradients: no scene parameter named '" + name +
                          "' (scene.parameters() lists them)");
    const std::string leaf = leafOf(name);
    // Which parameters are differentiable: their declarations say (parameters()).
    if (!known[py::str(name)]["differentiable"].cast<bool>())
      throw py::value_error(name +
                            ": not differentiated: only appearance parameters are (reflectance, "
                            "fluorescence, media, emission: docs/inverse.md); shape, camera, "
                            "settings and visibility need edge sampling or reparameterisation");
    for (const auto& p : r.parameters)
      if (p.name == name) throw py::value_error("gradients: '" + name + "' given twice");
    // A grid of values (a concentration map; a texture's texels): located by resolving the
    // scene with every value moved towards the middle of [0, 1]; one slot per value.
    auto addGrid = [&](const py::object& values, auto&& valueOf, auto&& add) {
      const py::object np = py::module_::import("numpy");
      const py::object a = np.attr("asarray")(values, "float64");
      const py::object moved =
          a.attr("__add__")(np.attr("where")(a.attr("__lt__")(0.5), 1e-3, -1e-3));
      std::optional<nx::RenderScene> changed;
      if (!resolvedWith(scene, name, valueOf(moved), fluorescence, changed))
        throw py::value_error(name + ": not differentiable: its values cannot be moved");
      GradientRequest::Parameter param;
      param.name = name;
      param.indexed = true;
      try {
        param.firstSlot = add(*changed);
      } catch (const nx::Error& e) {
        throw py::value_error(e.what());
      }
      param.slots = r.tangents.slots() - param.firstSlot;
      for (const py::handle d : a.attr("shape")) param.shape.push_back(d.cast<long>());
      r.parameters.push_back(param);
    };
    if (leaf == "concentration") {
      const py::object values = scene.attr("get")(name);
      if (values.is_none())
        throw py::value_error(name + ": not differentiable: the surface has no concentration "
                                     "map (set one, e.g. numpy.ones((32, 32)))");
      addGrid(
          values, [](const py::object& v) { return v; },
          [&](const nx::RenderScene& c) {
            return nx::addConcentrationSlots(r.tangents, name, base, c);
          });
      continue;
    }
    const Numbers numbers = numbersOf(scene.attr("get")(name), name);
    if (numbers.texture) {
      addGrid(
          numbers.textureValues,
          [&](const py::object& v) { return py::object(py::make_tuple(numbers.wavelengths, v)); },
          [&](const nx::RenderScene& c) { return nx::addTextureSlots(r.tangents, name, base, c); });
      continue;
    }
    GradientRequest::Parameter param{name, r.tangents.slots(),
                                     static_cast<uint32_t>(numbers.values.size()), numbers.indexed,
                                     numbers.shape};
    if (numbers.indexed) {
      // Written back as numbers, the parameter must give the scene it is (a table's
      // extrapolate="..." is not part of its numbers): else the derivative would be another
      // scene's.
      std::optional<nx::RenderScene> same;
      if (!resolvedWith(scene, name, numbers.valueOf(numbers.values), fluorescence, same))
        throw py::value_error(name + ": not differentiable: its value is refused when set back");
      nx::SceneTangents check = nx::SceneTangents::sizedFor(base);
      const nx::RenderScene* pair[] = {&*same, &base};
      const double unit[] = {1.0, -1.0};
      try {
        nx::addTangentSlot(check, name, base, pair, unit);
      } catch (const nx::Error&) {
        check.inert.clear();
      }
      if (check.inert.empty())
        throw py::value_error(name + ": not differentiable as written: set as its numbers it "
                                     "renders differently (e.g. a table's extrapolate=\"hold\" "
                                     "is not one of its numbers); write the table without it");
    }
    for (size_t j = 0; j < numbers.values.size(); ++j) {
      const double v = numbers.values[j];
      const double h = 1e-3 * std::max(std::abs(v), 1e-2);
      auto with = [&](double x, std::optional<nx::RenderScene>& out) {
        std::vector<double> values = numbers.values;
        values[j] = x;
        return resolvedWith(scene, name, numbers.valueOf(values), fluorescence, out);
      };
      std::optional<nx::RenderScene> a, b;
      std::vector<const nx::RenderScene*> scenes;
      std::vector<double> weights;
      // Central where both sides are allowed, else one-sided of second order.
      std::optional<nx::RenderScene> c;
      if (with(v + h, a) && with(v - h, b)) {
        scenes = {&*a, &*b};
        weights = {0.5 / h, -0.5 / h};
      } else if (with(v, c) && with(v - h, a) && with(v - 2 * h, b)) {
        scenes = {&*c, &*a, &*b};
        weights = {1.5 / h, -2 / h, 0.5 / h};
      } else if (with(v, c) && with(v + h, a) && with(v + 2 * h, b)) {
        scenes = {&*c, &*a, &*b};
        weights = {-1.5 / h, 2 / h, -0.5 / h};
      } else {
        throw py::value_error(name + ": cannot differentiate at " + std::to_string(v) +
                              ": no step of " + std::to_string(h) + " either way is allowed");
      }
      const std::string slotName = numbers.indexed ? name + "[" + std::to_string(j) + "]" : name;
      try {
        nx::addTangentSlot(r.tangents, slotName, base, scenes, weights);
      } catch (const nx::Error& e) {
        throw py::value_error(e.what());
      }
    }
    r.parameters.push_back(param);
  }
  if (r.parameters.empty()) throw py::value_error("gradients: expected at least one name");
  return r;
}

} // namespace nxpy
