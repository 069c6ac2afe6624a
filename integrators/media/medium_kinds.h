#pragma once
// The medium kinds a <medium type="..."> can name (homogeneous when absent): their specs,
// generated from one list of the kinds. Adding a kind: its struct (parameters, build, the
// coefficients the free-flight sampler evaluates) and its name in MediumKindList below; the
// render loop's media are HomogeneousMedium today, so a kind with another evaluation would
// also make RenderScene::media a variant over the kinds' evaluations (docs/architecture.md).

#include <array>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "core/kind_lookup.h"
#include "integrators/media/homogeneous_medium.h"

namespace nx {

/// The registered medium kinds.
using MediumKindList = std::tuple<HomogeneousMediumKind>;

/// A medium kind as the scene format sees it.
struct MediumKindSpec {
  const char* name;                            ///< as written in <medium type="...">
  const char* doc;                             ///< one line for the reference docs
  std::span<const TakenParameter> (*params)(); ///< the parameters it takes
  HomogeneousMedium (*build)(const ParameterSet&, const MediumInputs&); ///< from checked ones
};

namespace detail {
template <size_t... I>
std::array<MediumKindSpec, sizeof...(I)> mediumKindSpecs(std::index_sequence<I...>) {
  return {MediumKindSpec{std::tuple_element_t<I, MediumKindList>::kName,
                         std::tuple_element_t<I, MediumKindList>::kDoc,
                         &std::tuple_element_t<I, MediumKindList>::parameters,
                         &std::tuple_element_t<I, MediumKindList>::build}...};
}
} // namespace detail

/// Every medium kind, in MediumKindList's order.
inline std::span<const MediumKindSpec> mediumKinds() {
  static const auto specs =
      detail::mediumKindSpecs(std::make_index_sequence<std::tuple_size_v<MediumKindList>>());
  return specs;
}

/// The kind called `name`, or null.
inline const MediumKindSpec* findMediumKind(std::string_view name) {
  return findKindNamed(mediumKinds(), name);
}

/// "homogeneous": the kinds' names for messages.
inline std::string mediumKindList() {
  return kindNameList(mediumKinds());
}

/// The declaration of parameter `name` of `kind`, or null.
inline const TakenParameter* mediumParameter(const MediumKindSpec& kind, std::string_view name) {
  return findParameterNamed(kind.params(), name);
}

} // namespace nx
