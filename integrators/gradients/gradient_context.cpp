#include "integrators/gradients/gradient_context.h"

#include "integrators/gradients/light_gradients.h"

namespace nx {

GradientContext::GradientContext(const RenderScene& scene, const LightSampler& lights,
                                 const SceneTangents& t)
    : tangents(&t), shapes(!t.shapes.empty()) {
  static const SpectrumTangents none;
  for (int k = 0; k < lights.count(); ++k) {
    const SpectrumTangents* found = &none;
    const Spectrum* value = nullptr;
    const SpotLight* spot = nullptr;
    if (const int l = lights.sceneLightOf(k); l >= 0) {
      spot = std::get_if<SpotLight>(&scene.lights[static_cast<size_t>(l)]);
      value = differentiatedLightSpectrum(scene.lights[static_cast<size_t>(l)]);
      if (value) found = &t.lights[static_cast<size_t>(l)];
    } else {
      // An emitting shape or the background: the sampler refers to the scene's own spectrum.
      value = lights.emissionOf(k);
      for (size_t e = 0; e < scene.emission.size(); ++e)
        if (value == &scene.emission[e]) found = &t.emission[e];
      if (scene.background && value == &*scene.background) found = &t.background;
    }
    ofSampledLight.push_back(found);
    spectrumOfSampledLight.push_back(found->empty() ? nullptr : value);
    spotOfSampledLight.push_back(spot);
  }
}

} // namespace nx
