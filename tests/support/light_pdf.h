#pragma once
// The density a light sampler gives the surface a ray meets: what sample() must agree with.

#include "integrators/lights/light_sampler.h"

namespace nx::test {

/// The density LightSampler::pdf gives the surface a ray from p along wi meets (0 if none).
inline float pdfTowards(const RenderScene& s, const LightSampler& lights, const Vec3& p,
                        const Vec3& wi) {
  Ray r;
  r.o = p;
  r.d = wi;
  SurfaceHit hit;
  return s.geometry->intersect(r, hit) ? lights.pdf(p, hit, wi) : 0.0f;
}

} // namespace nx::test
