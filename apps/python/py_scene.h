#pragma once
// nxrender.Scene: a scene file loaded once and edited from Python (camera, materials,
// fluorescence, lights, settings) for parameter sweeps. Every edit is checked against the
// ranges the scene-file reader uses and recorded; the record enters the render key and the
// image's attributes, so images of edited scenes say what was changed.

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "apps/python/py_scene_items.h"
#include "integrators/scene_params/edited_scene.h"
#include "io/scene_desc.h"

namespace nxpy {

namespace py = pybind11;

/// A scene description and the edits made to it since it was read (the library's), with the
/// identities its views hold (py_scene_items.h).
struct SceneState : nx::EditedScene {
  ItemRegistry<nx::ObjectDesc> objectItems;
  ItemRegistry<nx::LightDesc> lightItems;
};
using nx::editsText;
using nx::sceneForRendering;

/// The Python object behind nxrender.Scene (shared by its views: objects, camera, ...).
struct PyScene {
  std::shared_ptr<SceneState> state;
};

/// Registers Scene and its views.
void bindScene(py::module_& m);

} // namespace nxpy
