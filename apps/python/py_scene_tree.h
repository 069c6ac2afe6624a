#pragma once
// Python values <-> scene trees (io/scene_tree.h), generically: dicts, lists and tuples,
// numbers, strings, bools, None and numpy arrays. No parameter is named here: what a key means
// is the scene format's business (the one reader checks it).

#include <pybind11/pybind11.h>

#include <string>

#include "io/scene_tree.h"

namespace nxpy {

namespace py = pybind11;

/// The tree of a Python value; TypeError naming `path` for a value of no tree form.
nx::SceneTree treeFromPython(const py::handle& value, const std::string& path);

/// The Python value of a tree: dicts, lists, floats (ints where whole and the key is a count),
/// strings, numpy arrays.
py::object treeToPython(const nx::SceneTree& tree);

} // namespace nxpy
