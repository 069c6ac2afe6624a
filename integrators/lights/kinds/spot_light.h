#pragma once
// A spot light (a lab lamp): a point source whose intensity falls off with the angle theta from
// its axis, I(lambda, theta) = I(lambda) s(cos theta), s the smoothstep from 0 at the cone's
// edge to 1 inside the falloff start (pbrt-v4's SpotLight), its spectrum measured (a CSV) or
// given.

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/text_table.h"
#include "integrators/lights/light_kind.h"

namespace nx {

/// A cone narrower than 0.03 degrees is not resolved in single precision (its cosine rounds to 1
/// below about 0.014 degrees): it would light nothing.
inline constexpr ParameterRange kSpotAngleRange{0.03, 90, false, "a half-angle in degrees"};
inline constexpr ParameterRange kSpotFalloffRange{0, 90, false, "a half-angle in degrees"};

/// A spot light.
struct SpotLight {
  Vec3 position;
  Vec3 axis;                 ///< the unit direction it points along
  Spectrum intensity;        ///< on the axis
  float cosEdge = 0;         ///< cos of the cone's half-angle: nothing beyond it
  float cosFalloffStart = 1; ///< cos of the half-angle within which the intensity is whole

  static constexpr bool kInfinite = false;
  static constexpr const char* kName = "spot";
  static constexpr const char* kDoc =
      "a spot light (a lamp): intensity I on its axis, falling off smoothly to 0 at the cone's "
      "edge";
  /// Its parameters.
  static std::span<const LightParameter> parameters() {
    static const LightParameter p[] = {
        kLightPosition,
        {{"look_at", ParamType::Point, "scene units", nullptr, "a point on its axis", "0, 0, 0"},
         "",
         true},
        {{"cone_angle", ParamType::Number, "degrees", &kSpotAngleRange,
          "half-angle of the cone it lights (0 beyond it)", "30"},
         "30"},
        {{"falloff_angle", ParamType::Number, "degrees", &kSpotFalloffRange,
          "half-angle within which the intensity is whole (smoothstep to the edge)", "20"},
         "cone_angle"},
        {differentiable(
             {"color", ParamType::Rgb, "W sr^-1 nm^-1", nullptr,
              "RGB intensity on the axis (rt and mcpt; spectral_mcpt without <emission>)",
              "40, 40, 40"}),
         ""},
        {differentiable(
             {"emission", ParamType::Spectrum, "W sr^-1 nm^-1", nullptr,
              "spectral intensity on the axis (a measured lamp: csv=\"...\"); scale=\"...\" "
              "multiplies it",
              "A"}),
         ""},
        kLightEmissionScale,
        kLightEmissionAt,
    };
    return p;
  }
  /// Builds it from its checked parameters.
  static SpotLight build(const ParameterSet& p, const LightInputs& in) {
    if (!p.has("emission") && !p.has("color"))
      throw Error(in.loc.str() + ": expected <emission> or <color> on a spot light, found neither");
    const Vec3d from = *p.get<Vec3d>("position"), to = *p.get<Vec3d>("look_at");
    if (!(length(to - from) > 0))
      throw Error(p.locOf("look_at", in.loc).str() +
                  ": expected a look_at point apart from the spot light's position");
    const double edge = p.number("cone_angle").value_or(30.0);
    const double start = p.number("falloff_angle").value_or(edge);
    if (start > edge)
      throw Error(p.locOf("falloff_angle", in.loc).str() +
                  ": expected a falloff_angle at most the cone_angle (" + numberText(edge) +
                  " degrees), found " + numberText(start));
    SpotLight s;
    s.position = Vec3(from);
    s.axis = Vec3(normalize(to - from));
    s.intensity = lightIntensity(p, in);
    s.cosEdge = static_cast<float>(std::cos(edge * kPi / 180));
    // (kSpotAngleRange keeps the cone resolved; Python edits are range-checked too.)
    if (!(s.cosEdge < 1))
      throw Error(p.locOf("cone_angle", in.loc).str() +
                  ": expected a cone_angle of at least 0.03 degrees (a narrower cone is not "
                  "resolved in single precision and would light nothing), found " +
                  numberText(edge));
    s.cosFalloffStart = static_cast<float>(std::cos(start * kPi / 180));
    return s;
  }

  /// The fraction of the axis intensity sent at cos theta from the axis.
  float falloff(float cosTheta) const {
    if (cosTheta >= cosFalloffStart) return 1;
    if (cosTheta <= cosEdge) return 0;
    const float t = (cosTheta - cosEdge) / (cosFalloffStart - cosEdge);
    return t * t * (3 - 2 * t);
  }
  /// Where Local light selection weighs it from: its position, no extent.
  Vec3 center() const { return position; }
  /// The directions it sends light into: its cone (for the light tree, with theta_e = 0).
  DirectionCone emissionCone() const { return {axis, cosEdge}; }
  /// The fraction of its axis intensity it sends towards p (0 outside its cone).
  float fractionToward(const Vec3& p) const {
    const Vec3 d = p - position;
    const float d2 = dot(d, d);
    return d2 > 0 ? falloff(dot(d, axis) / std::sqrt(d2)) : 0.0f;
  }
  /// The traced-range integral of its peak intensity (W sr^-1).
  double tracedPeak() const { return tracedIntegral(intensity); }
  /// Emitted power over the traced range (W): 2 pi times the integral of the falloff over
  /// cos theta, found by the midpoint rule.
  double power(double = 0) const {
    double integral = 0;
    const int steps = 1000;
    for (int i = 0; i < steps; ++i) {
      const float c = cosEdge + (1 - cosEdge) * (static_cast<float>(i) + 0.5f) / steps;
      integral += falloff(c) * (1 - cosEdge) / steps;
    }
    return 2 * kPi * integral * tracedPeak();
  }
  /// The direction from p to it and I s(cos theta) / d^2 (a delta: pdf 1).
  bool sample(const Vec3& p, Sample2, const SampledWavelengths& lambda, LightSample& out) const {
    return sampleDeltaLight(position, intensity, p, lambda, out,
                            [&](const Vec3& wi) { return falloff(-dot(wi, axis)); });
  }
};

} // namespace nx
