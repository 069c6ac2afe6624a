#include "core/ray_offset.h"
#include "integrators/lights/light_sample.h"

namespace nx {

Ray shadowRayTo(const Vec3& p, const Vec3& pError, const Vec3& n, const LightSample& ls) {
  Ray r;
  if (ls.infinite) {
    r.o = offsetRayOrigin(p, pError, n, ls.wi);
    r.d = ls.wi;
    r.tMax = INFINITY;
    return r;
  }
  r.o = offsetRayOrigin(p, pError, n, ls.wi);
  const Vec3 end = ls.delta ? ls.p : offsetRayOrigin(ls.p, ls.pError, ls.n, r.o - ls.p);
  r.d = end - r.o;
  r.tMin = 0;
  r.tMax = 1 - kShadowEpsilon;
  return r;
}

} // namespace nx
