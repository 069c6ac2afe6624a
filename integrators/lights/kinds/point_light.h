#pragma once
// A point light (Niixtracer's <light>): radiant intensity I(lambda) in W sr^-1 nm^-1, the same
// in every direction, at a position.

#include <cmath>

#include "integrators/lights/light_kind.h"

namespace nx {

/// A point light.
struct PointLight {
  Vec3 position;
  Spectrum intensity;

  static constexpr const char* kName = "point";
  static constexpr const char* kDoc =
      "a point light: intensity I in W sr^-1 nm^-1 in every direction (Niixtracer's <light>)";
  /// Its parameters.
  static std::span<const LightParameter> parameters() {
    static const LightParameter p[] = {
        kLightPosition,
        {differentiable({"color", ParamType::Rgb, "W sr^-1 nm^-1", nullptr,
                         "RGB intensity (rt and mcpt; spectral_mcpt without <emission>)",
                         "40, 40, 40"}),
         "", true},
        {differentiable({"emission", ParamType::Spectrum, "W sr^-1 nm^-1", nullptr,
                         "spectral intensity (spectral_mcpt); scale=\"...\" multiplies it", "D65"}),
         ""},
        kLightEmissionScale,
        kLightEmissionAt,
    };
    return p;
  }
  /// Builds it from its checked parameters.
  static PointLight build(const ParameterSet& p, const LightInputs& in) {
    return {Vec3(*p.get<Vec3d>("position")), lightIntensity(p, in)};
  }

  /// Where Local light selection weighs it from: its position, no extent.
  Vec3 center() const { return position; }
  /// The directions it sends light into (every one) and how far beyond them (cos theta_e,
  /// LightBounds), for the light tree.
  DirectionCone emissionCone() const { return DirectionCone::all(); }
  /// The fraction of its peak intensity it sends towards p (1: the same everywhere).
  float fractionToward(const Vec3&) const { return 1; }
  /// The traced-range integral of its peak intensity (W sr^-1).
  double tracedPeak() const { return tracedIntegral(intensity); }
  /// Emitted power over the traced range (W).
  double power(double = 0) const { return 4 * kPi * tracedPeak(); }
  static constexpr bool kInfinite = false;
  /// The direction from p to it and I / d^2 (a delta: pdf 1).
  bool sample(const Vec3& p, Sample2, const SampledWavelengths& lambda, LightSample& out) const {
    return sampleDeltaLight(position, intensity, p, lambda, out, [](const Vec3&) { return 1.0f; });
  }
};

} // namespace nx
