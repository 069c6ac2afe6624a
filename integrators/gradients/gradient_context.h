#pragma once
// What the path tracer needs to differentiate a render: the scene's tangents and, per light
// the light sampler can choose, the tangents of the spectrum it emits.

#include <vector>

#include "integrators/gradients/scene_tangents.h"
#include "integrators/lights/light_sampler.h"

namespace nx {

/// The tangents in the form the render loop reads them (no lookup per vertex).
struct GradientContext {
  const SceneTangents* tangents = nullptr;
  /// Per LightSampler light: the tangents of its emission (empty for none) and the spectrum
  /// they are derivatives of (its radiance or intensity; null when not differentiated).
  std::vector<const SpectrumTangents*> ofSampledLight;
  std::vector<const Spectrum*> spectrumOfSampledLight;
  /// Some slot moves the geometry: paths carry their vertices' motion (geometry_gradients.h).
  bool shapes = false;
  /// Shape derivatives' boundary terms are sampled (RenderOptions::shapeBoundary).
  bool boundary = true;
  /// Per LightSampler light: the spot light it is (its falloff moves with the lit point), or
  /// null.
  std::vector<const SpotLight*> spotOfSampledLight;

  /// The context for `scene` rendered with `lights`.
  GradientContext(const RenderScene& scene, const LightSampler& lights,
                  const SceneTangents& tangents);
};

} // namespace nx
