#pragma once
// Every parameter of a scene by its stable name, with its declaration: what
// Scene.parameters() lists, what get/set by name and the gradient set-up accept. Shape,
// material, light and medium parameters come from the kinds' declarations; the others from
// core/params/scene_parameters.h.

#include <string>
#include <vector>

#include "core/params/scene_limits.h"
#include "io/scene_desc.h"

namespace nx {

/// One parameter of a scene: its name and declaration.
struct SceneParameterInfo {
  std::string name; ///< "spp", "camera.fov", "objects[1].fluorescence.stokes_nm", ...
  std::string type; ///< "number", "spectrum", "point", ... (paramTypeName or the table's)
  std::string unit;
  std::string doc;
  std::string defaultText;               ///< the kind's default as a scene writes it, or ""
  const ParameterRange* range = nullptr; ///< numbers: the allowed values
  bool differentiable = false;           ///< renders give derivatives with respect to it
};

/// The parameters of `d` in a stable order: settings, named spectra, the camera, each object
/// (shape, emission, material, medium), named materials, lights. Material parameters a kind
/// takes are listed whether given or not.
std::vector<SceneParameterInfo> sceneParameters(const SceneDesc& d);

/// The declaration of `d`'s parameter `name` (in any quoting, canonicalParameterName); throws
/// nx::Error "no scene parameter named '...' (Scene.parameters() lists them)".
SceneParameterInfo sceneParameter(const SceneDesc& d, const std::string& name);

} // namespace nx
