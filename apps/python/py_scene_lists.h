#pragma once
// scene.objects and scene.lights: live sequences of a scene's objects and lights (append,
// insert, del, pop, item assignment of a view or a dict), every change checked as a scene file
// is and recorded as edits are.

#include "apps/python/py_scene_views.h"

namespace nxpy {

/// Registers the list types (bindScene calls it before the Scene class uses them).
void bindSceneLists(py::module_& m);

/// The live list of a scene's objects / lights.
py::object objectList(const StatePtr& s);
py::object lightList(const StatePtr& s);

} // namespace nxpy
