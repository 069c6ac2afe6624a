#pragma once
// The scene's lists (objects, lights) and tables (spectra, materials) as Python sees them:
// views that can be read and indexed, and whose every mutating method raises a TypeError
// saying what to do instead (they were copies: scene.objects.append(o) succeeded and did
// nothing).

#include <pybind11/pybind11.h>

#include <string>

namespace nxpy {

namespace py = pybind11;

/// A read-only sequence of items named `name` ("scene.objects").
struct ReadOnlyList {
  py::tuple items;
  std::string name;
};

/// A read-only mapping named `name` ("scene.materials").
struct ReadOnlyMapping {
  py::dict items;
  std::string name;
};

/// Registers both classes (SceneList and SceneMapping) in the module.
void bindReadOnlyContainers(py::module_& m);

} // namespace nxpy
