// Visibility through media and interfaces.

#include "integrators/media/transmittance.h"

#include <cmath>

#include "core/ray_offset.h"
#include "integrators/lights/light_sample.h"
#include "integrators/materials/bsdf.h"

namespace nx {

SampledSpectrum mediumTransmittance(const RenderScene& scene, int medium,
                                    const SampledWavelengths& lambda, float length) {
  SampledSpectrum T = SampledSpectrum::filled(1.0f);
  if (medium < 0) return T;
  SampledSpectrum a, s, fl;
  scene.media[static_cast<size_t>(medium)].coefficients(lambda, a, s, fl);
  for (int i = 0; i < kLanes; ++i) {
    const float st = a[i] + s[i];
    T[i] = st > 0 ? (std::isinf(length) ? 0.0f : std::exp(-st * length)) : 1.0f;
  }
  return T;
}

SampledSpectrum shadowTransmittance(const RenderScene& scene, const Ray& ray, MediumStack media,
                                    const SampledWavelengths& lambda, TraceCounters& counters,
                                    ShadowCrossings* crossings) {
  SampledSpectrum T = SampledSpectrum::filled(1.0f);
  const bool infinite = std::isinf(ray.tMax);
  const Vec3 end = infinite ? Vec3() : ray.o + ray.d; // the segment ends near t = 1
  Ray r = ray;
  for (int crossing = 0; crossing <= kMaxPathBounces; ++crossing) {
    SurfaceHit hit;
    ++counters.rays;
    const bool found = scene.geometry->intersect(r, hit);
    const float t = found ? hit.t : r.tMax;
    const float segment = std::isinf(t) ? t : t * length(r.d);
    T *= mediumTransmittance(scene, media.current(), lambda, segment);
    if (crossings && media.current() >= 0) crossings->media.emplace_back(media.current(), segment);
    if (!found || T.isBlack()) return T;
    const Material& material = scene.materials[scene.appearance(hit).material];
    // Only a straight transmission (an interface, a thin wall) lets a shadow ray through.
    const uint8_t lobes = materialLobes(material);
    if (!(lobes & kStraightTransmission)) return {};
    if (!passesUnchanged(lobes)) {
      if (crossings) crossings->walls.push_back(scene.appearance(hit).material);
      const float c = std::abs(dot(r.d, hit.ng)) / length(r.d);
      T *= straightTransmittance(material, lambda, c);
      if (T.isBlack()) return T;
    }
    if (const ShapeAppearance& app = scene.appearance(hit); app.boundary != 0) {
      if (dot(r.d, hit.ng) * static_cast<float>(app.boundary) < 0)
        media.enter(app.medium);
      else
        media.leave();
    }
    r.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, r.d);
    if (!infinite) {
      r.d = end - r.o;
      r.tMax = 1 - kShadowEpsilon;
    }
    r.tMin = 0;
  }
  return {};
}

} // namespace nx
