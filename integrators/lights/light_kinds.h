#pragma once
// The light kinds a scene's <light type="..."> can name: one variant over the kinds (static
// dispatch, no virtual call while rendering) and their specs, generated from it. Adding a kind:
// its header in kinds/ and its name in SceneLight below (docs/architecture.md).

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "core/kind_lookup.h"

#include "integrators/lights/kinds/environment_light.h"
#include "integrators/lights/kinds/point_light.h"
#include "integrators/lights/kinds/spot_light.h"

namespace nx {

/// A light of the scene's light list (not a shape's emission, not the uniform background).
using SceneLight = std::variant<PointLight, SpotLight, EnvironmentLight>;

/// A light kind as the scene format sees it.
struct LightKindSpec {
  const char* name;                            ///< as written in <light type="...">
  const char* doc;                             ///< one line for the reference docs
  std::span<const LightParameter> (*params)(); ///< the parameters it takes
  SceneLight (*build)(const ParameterSet& p, const LightInputs& in); ///< from checked parameters
};

namespace detail {
template <class Kind>
LightKindSpec lightKindSpec() {
  return {Kind::kName, Kind::kDoc, &Kind::parameters,
          [](const ParameterSet& p, const LightInputs& in) -> SceneLight {
            return Kind::build(p, in);
          }};
}
template <size_t... I>
std::array<LightKindSpec, sizeof...(I)> lightKindSpecs(std::index_sequence<I...>) {
  return {lightKindSpec<std::variant_alternative_t<I, SceneLight>>()...};
}
} // namespace detail

/// Every light kind, in the variant's order.
inline std::span<const LightKindSpec> lightKinds() {
  static const auto specs =
      detail::lightKindSpecs(std::make_index_sequence<std::variant_size_v<SceneLight>>());
  return specs;
}

/// The kind called `name`, or null.
inline const LightKindSpec* findLightKind(std::string_view name) {
  return findKindNamed(lightKinds(), name);
}

/// "point, spot or environment": the kinds' names for messages.
inline std::string lightKindList() {
  return kindNameList(lightKinds());
}

/// The declaration of parameter `name` of `kind`, or null.
inline const LightParameter* lightParameter(const LightKindSpec& kind, std::string_view name) {
  return findParameterNamed(kind.params(), name);
}

} // namespace nx
