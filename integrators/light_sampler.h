#pragma once
// Next-event estimation: choosing a light and a direction towards it.

#include <vector>

#include "core/sampler.h"
#include "integrators/render_scene.h"
#include "spectra/sampled_wavelengths.h"

namespace nx {

/// A direction towards a light, with what arrives along it.
struct LightSample {
  Vec3 wi;                  ///< unit direction from the shading point
  float distance = 0;       ///< to the light's surface or position (shadow ray length)
  SampledSpectrum radiance; ///< emitted radiance (area lights) or I / d^2 (point lights)
  float pdf = 0; ///< solid-angle density including the light choice; for point lights the choice
                 ///< probability
  bool delta = false;                         ///< a point light: cannot be hit by BSDF sampling
  uint32_t sphere = GeometryScene::kNoSphere; ///< the emitting sphere aimed at, if any
};

/// The lights next-event estimation can aim at: emitting spheres (sampled through the cone
/// they subtend, or uniformly over directions from inside) and point lights, chosen
/// uniformly. Emitting planes and triangles and the background are reached by BSDF sampling
/// only.
class LightSampler {
public:
  explicit LightSampler(const RenderScene& scene);

  /// Number of lights it can choose from.
  int count() const { return static_cast<int>(lights_.size()); }

  /// A light sample for shading point p; false if no light or a degenerate configuration.
  bool sample(const Vec3& p, float uChoice, Sample2 u, const SampledWavelengths& lambda,
              LightSample& out) const;

  /// Density (solid angle, with the choice probability) with which sample() would return
  /// direction wi towards emitting sphere `sphereIndex` from p; 0 if it is not a light.
  float pdfSphere(const Vec3& p, uint32_t sphereIndex, const Vec3& wi) const;

private:
  struct Light {
    bool point;
    uint32_t index; ///< sphere index or point light index
  };
  const RenderScene* scene_;
  std::vector<Light> lights_;
  std::vector<int32_t> sphereLight_; ///< light number per sphere, or -1
};

} // namespace nx
