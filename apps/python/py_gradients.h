#pragma once
// The parameters a differentiated render (render(gradients=...), backward) is asked for, from
// Python: the names checked as Python's, then the library's set-up
// (integrators/gradients/gradient_setup.h).

#include <string>
#include <vector>

#include "apps/python/py_image.h"
#include "apps/python/py_scene.h"
#include "integrators/gradients/scene_tangents.h"

namespace nxpy {

/// The slots of a differentiated render and the scene's tangents for them.
using GradientRequest = nx::GradientSetup;

/// The request for `names` (a list of str, as scene.parameters() names them) on `scene` (an
/// nxrender.Scene), whose built scene is `base`. `fluorescence` false: the scenes are resolved
/// without it (as the render). Raises KeyError for unknown names, ValueError for parameters
/// that are not differentiated (geometry, camera, settings, names of spectra), naming them.
GradientRequest gradientRequest(const py::object& scene, const py::handle& names,
                                const nx::RenderScene& base, bool fluorescence);

} // namespace nxpy
