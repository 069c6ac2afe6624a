#pragma once
// The scene's tables (spectra, materials) as Python sees them: views that can be read and
// indexed, and whose every mutating method raises a TypeError saying what to do instead (they
// were copies: a change succeeded and did nothing). The objects and lights are live lists
// (apps/python/py_scene_lists.h).

#include <pybind11/pybind11.h>

#include <string>

namespace nxpy {

namespace py = pybind11;

/// A read-only mapping named `name` ("scene.materials").
struct ReadOnlyMapping {
  py::dict items;
  std::string name;
};

/// Registers the SceneMapping class in the module.
void bindReadOnlyContainers(py::module_& m);

} // namespace nxpy
