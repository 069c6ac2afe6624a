#pragma once
// The name of a light group's component layer (--aov lightgroups): light.NAME. Its channels
// are light.NAME.S0.<band>nm (io/exr_names.h bounds the names' length).

#include <string>

namespace nx {

/// Prefix of a light group's layer name.
inline constexpr const char* kLightLayerPrefix = "light.";

/// The layer of the light group called `group`.
inline std::string lightLayerName(const std::string& group) {
  return kLightLayerPrefix + group;
}

} // namespace nx
