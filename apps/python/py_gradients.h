#pragma once
// The parameters a differentiated render (render(gradients=...), backward) is asked for: their
// names expanded into slots (one per number: a scalar, a knot of a tabulated spectrum, a colour
// channel) and the scene's tangents for them, made by resolving copies of the scene with each
// number moved a little (integrators/gradients/scene_tangents.h).

#include <string>
#include <vector>

#include "apps/python/py_image.h"
#include "apps/python/py_scene.h"
#include "integrators/gradients/scene_tangents.h"

namespace nxpy {

/// The slots of a differentiated render.
struct GradientRequest {
  /// Per requested name: its canonical name, first slot and number of slots; `indexed` when
  /// it is a vector (a spectrum's values, a colour) whose gradient has a leading component axis.
  using Parameter = GradientParameter;
  std::vector<Parameter> parameters;
  nx::SceneTangents tangents;
};

/// The request for `names` (a list of str, as scene.parameters() names them) on `scene` (an
/// nxrender.Scene), whose built scene is `base`. `fluorescence` false: the scenes are resolved
/// without it (as the render). Raises KeyError for unknown names, ValueError for parameters
/// that are not differentiated (geometry, camera, settings, names of spectra), naming them.
GradientRequest gradientRequest(const py::object& scene, const py::handle& names,
                                const nx::RenderScene& base, bool fluorescence);

} // namespace nxpy
