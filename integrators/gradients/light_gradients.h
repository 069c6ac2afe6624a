#pragma once
// What the gradient code knows of each light kind: the spectrum it differentiates (or none),
// whether two builds place the light alike, and which other change it refuses. Every kind of
// SceneLight must specialise LightGradient: a new light kind without one does not compile, so
// it is either handled or refused by name (a gradient request in a scene holding a kind the
// code did not list threw std::bad_variant_access).

#include <string>
#include <type_traits>

#include "integrators/lights/light_kinds.h"

namespace nx {

/// The gradient code's view of light kind `Kind` (specialised below for each kind).
template <class Kind>
struct LightGradient {
  static_assert(sizeof(Kind) == 0,
                "declare how gradients treat this light kind: specialise LightGradient<Kind> in "
                "integrators/gradients/light_gradients.h");
};

/// A point light: its intensity is differentiated; its position must not change.
template <>
struct LightGradient<PointLight> {
  static const Spectrum* spectrum(const PointLight& l) { return &l.intensity; }
  static bool samePlacement(const PointLight& a, const PointLight& b) {
    return a.position.x == b.position.x && a.position.y == b.position.y &&
           a.position.z == b.position.z;
  }
  static std::string otherChange(const PointLight&, const PointLight&) { return ""; }
};

/// A spot light: its intensity is differentiated; its position, axis and cone must not change.
template <>
struct LightGradient<SpotLight> {
  static const Spectrum* spectrum(const SpotLight& l) { return &l.intensity; }
  static bool samePlacement(const SpotLight& a, const SpotLight& b) {
    return a.position.x == b.position.x && a.position.y == b.position.y &&
           a.position.z == b.position.z && a.axis.x == b.axis.x && a.axis.y == b.axis.y &&
           a.axis.z == b.axis.z && a.cosEdge == b.cosEdge && a.cosFalloffStart == b.cosFalloffStart;
  }
  static std::string otherChange(const SpotLight&, const SpotLight&) { return ""; }
};

/// An environment map: not differentiated; a change of its radiance is refused by name.
template <>
struct LightGradient<EnvironmentLight> {
  static const Spectrum* spectrum(const EnvironmentLight&) { return nullptr; }
  static bool samePlacement(const EnvironmentLight&, const EnvironmentLight&) { return true; }
  static std::string otherChange(const EnvironmentLight& a, const EnvironmentLight& b) {
    const bool same = a.integral == b.integral && a.texels && b.texels && *a.texels == *b.texels;
    return same ? "" : "an environment map";
  }
};

/// The differentiated spectrum of a light (null for kinds not differentiated).
inline const Spectrum* differentiatedLightSpectrum(const SceneLight& l) {
  return std::visit(
      [](const auto& k) { return LightGradient<std::decay_t<decltype(k)>>::spectrum(k); }, l);
}

/// True when two builds of a light have its kind and its placement.
inline bool sameLightPlacement(const SceneLight& a, const SceneLight& b) {
  if (a.index() != b.index()) return false;
  return std::visit(
      [&](const auto& k) {
        using Kind = std::decay_t<decltype(k)>;
        return LightGradient<Kind>::samePlacement(k, std::get<Kind>(b));
      },
      a);
}

/// What else changed between two builds of a light that gradients refuse ("" : nothing).
inline std::string otherLightChange(const SceneLight& a, const SceneLight& b) {
  if (a.index() != b.index()) return "a light's kind";
  return std::visit(
      [&](const auto& k) {
        using Kind = std::decay_t<decltype(k)>;
        return LightGradient<Kind>::otherChange(k, std::get<Kind>(b));
      },
      a);
}

} // namespace nx
