// Slots and tangents of a differentiated render from Python: the names checked (a list of
// str, each a parameter of the scene: KeyError otherwise), then the library's set-up
// (integrators/gradients/gradient_setup.h), whose refusals become ValueError.

#include "apps/python/py_gradients.h"

#include <pybind11/stl.h>

#include <algorithm>

#include "core/error.h"
#include "integrators/scene_params/parameter_path.h"
#include "integrators/scene_params/scene_parameter_list.h"

namespace nxpy {

GradientRequest gradientRequest(const py::object& scene, const py::handle& names,
                                const nx::RenderScene& base, bool fluorescence) {
  if (py::isinstance<py::str>(names) || !py::hasattr(names, "__iter__"))
    throw py::type_error("gradients: expected a list of parameter names (scene.parameters()), "
                         "found " +
                         std::string(py::str(py::type::of(names).attr("__name__"))));
  const nx::SceneDesc desc = sceneForRendering(*scene.cast<const PyScene&>().state);
  const std::vector<nx::SceneParameterInfo> known = nx::sceneParameters(desc);
  std::vector<std::string> list;
  for (const py::handle item : names) {
    if (!py::isinstance<py::str>(item)) throw py::type_error("gradients: expected parameter names");
    const std::string name = nx::canonicalParameterName(item.cast<std::string>());
    if (std::none_of(known.begin(), known.end(),
                     [&](const nx::SceneParameterInfo& p) { return p.name == name; }))
      throw py::key_error("gradients: no scene parameter named '" + name +
                          "' (scene.parameters() lists them)");
    list.push_back(name);
  }
  py::gil_scoped_release release;
  try {
    return nx::gradientSetup(desc, list, base, fluorescence);
  } catch (const nx::Error& e) {
    throw py::value_error(e.what()); // a C++ exception: pybind11 translates it with the GIL
    // taken back
  }
}

} // namespace nxpy
