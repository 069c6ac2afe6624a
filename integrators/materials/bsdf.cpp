#include "integrators/materials/bsdf.h"

#include <algorithm>
#include <cmath>

namespace nx {

SurfaceBsdf::SurfaceBsdf(const Material& m, const SampledWavelengths& lambda,
                         const SampledSpectrum& rho, const Vec3& ng, const Vec3& ns, const Vec3& wo,
                         TransportMode mode) {
  s_.material = &m;
  s_.lambda = &lambda;
  s_.rho = rho;
  s_.ng = ng;
  s_.n = ns;
  s_.wo = wo;
  s_.mode = mode;
  visitScatteringModel(m.kind, [&](auto model) {
    using Model = decltype(model);
    s_.lobes = Model::lobes(m);
    Model::prepare(s_);
  });
}

uint8_t materialLobes(const Material& m) {
  return visitScatteringModel(m.kind, [&](auto model) { return decltype(model)::lobes(m); });
}

SampledSpectrum straightTransmittance(const Material& m, const SampledWavelengths& lambda,
                                      float cosine) {
  return visitScatteringModel(m.kind, [&](auto model) {
    return decltype(model)::straightTransmittance(m, lambda, cosine);
  });
}

bool albedoIsReflectance(const Material& m) {
  return visitScatteringModel(m.kind,
                              [&](auto model) { return decltype(model)::albedoIsReflectance(m); });
}

bool roughnessDifferentiable(const Material& m) {
  return visitScatteringModel(
      m.kind, [&](auto model) { return decltype(model)::roughnessDifferentiable(m); });
}

BsdfDerivativeSteps bsdfDerivativeSteps(const Material& m) {
  return visitScatteringModel(m.kind,
                              [&](auto model) { return decltype(model)::derivativeSteps(m); });
}

void SurfaceBsdf::orient(const Vec3& dpdu) {
  if (s_.alpha.ax == s_.alpha.ay) return; // isotropic (or smooth, or not a microfacet surface)
  const Vec3 t = dpdu - s_.n * dot(dpdu, s_.n);
  const float len = length(t);
  if (!(len > 1e-12f) || !std::isfinite(len)) return;
  s_.frame.s = t * (1.0f / len);
  s_.frame.t = cross(s_.n, s_.frame.s);
}

float inverseReflectanceSlope(float rho, bool albedo, bool& zero) {
  zero = false;
  if (!albedo) return 0.0f;
  if (rho > 0) return 1.0f / rho;
  zero = true;
  return 0.0f;
}

GgxDistribution clampedGgx(const Material& m) {
  // Rougher than 1e-4 is a microfacet surface (clamped there), else a smooth one.
  if (!roughMicrofacets(m)) return {};
  return {std::max(m.alphaU, 1e-4f), std::max(m.alphaV, 1e-4f)};
}

BsdfDerivativeSteps microfacetDerivativeSteps(const Material& m) {
  if (!roughMicrofacets(m)) return {}; // smooth (clampedGgx)
  const float width = std::max(std::min(m.alphaU, m.alphaV), 1e-4f);
  return {std::min(1e-3f, width / 8), std::min(1e-3f, width / 8)};
}

} // namespace nx
