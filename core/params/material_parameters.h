#pragma once
// The scene format's material parameters: one declaration per name (type, unit, range,
// meaning), read by the scene loader, checked by the Python module, listed in the reference
// docs. Which kinds take which of them: integrators/materials/material_kind.h.

#include <span>
#include <string_view>

#include "core/params/parameter_set.h"

namespace nx {

/// Every material parameter name, in the order the reference docs and errors list them.
std::span<const ParamSpec> materialParameters();

/// The declaration of a material parameter name, or null if there is none.
const ParamSpec* materialParameter(std::string_view name);

} // namespace nx
