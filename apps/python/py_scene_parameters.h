#pragma once
// Scene.parameters(), Scene.get(name) and Scene.set(name, value): the scene's parameters by
// stable names (cf. Mitsuba 3's mi.traverse).

#include "apps/python/py_scene.h"

namespace nxpy {

/// Adds parameters(), get() and set() to nxrender.Scene (bindScene must have run).
void bindSceneParameters(py::module_& m);

} // namespace nxpy
