#pragma once
// The scene's parameters that are not a material kind's (settings, camera, shapes, media,
// fluorescence fields, point lights): one declaration each, for Python's Scene.parameters()
// and the reference docs (docs/reference/python-parameters.md). Material parameters:
// core/params/material_parameters.h and the kinds' schemas.

#include <span>
#include <string>

#include "core/params/scene_limits.h"

namespace nx {

/// A parameter that is not a material's: the leaf of its name with the kind of item it
/// belongs to, how it is written, its unit, range and meaning.
struct FixedParameter {
  const char* key;  ///< "spp", "camera.fov", "object.radius", "medium.g", "light.position", ...
  const char* type; ///< "number", "point", "spectrum", ...
  const char* unit;
  const ParameterRange* range; ///< numbers: the allowed values; null otherwise
  const char* doc;
  bool differentiable = false; ///< renders give derivatives with respect to it
};

/// Every such parameter, in the order they are listed.
std::span<const FixedParameter> fixedParameters();

/// The declaration called `key`; throws std::logic_error if there is none (a defect).
const FixedParameter& fixedParameter(const std::string& key);

} // namespace nx
