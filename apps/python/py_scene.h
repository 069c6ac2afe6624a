#pragma once
// nxrender.Scene: a scene file loaded once and edited from Python (camera, materials,
// fluorescence, lights, settings) for parameter sweeps. Every edit is checked against the
// ranges the scene-file reader uses and recorded; the record enters the render key and the
// image's attributes, so images of edited scenes say what was changed.

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "io/scene_desc.h"

namespace nxpy {

namespace py = pybind11;

/// A scene description and the edits made to it since it was read.
struct SceneState {
  nx::SceneDesc desc;
  std::vector<std::string> edits; ///< "objects[2].fluorescence.stokes_nm = 60", in order
  /// Counts of insertions into and removals from the object and light lists (views taken
  /// before one refuse to be used)
  uint64_t objectsVersion = 0, lightsVersion = 0;
};

/// The Python object behind nxrender.Scene (shared by its views: objects, camera, ...).
struct PyScene {
  std::shared_ptr<SceneState> state;
};

/// The description to render: a copy of the scene's with the digest of its state (the render
/// key follows the state, as a file's does, not the edit log).
nx::SceneDesc sceneForRendering(const SceneState& state);

/// The edits as one attribute value ("" when there are none).
std::string editsText(const SceneState& state);

/// Registers Scene and its views.
void bindScene(py::module_& m);

} // namespace nxpy
