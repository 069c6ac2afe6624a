#include "integrators/light_sampler.h"

#include <cmath>

#include "core/frame.h"
#include "integrators/integrator.h"
#include "integrators/sampling.h"

namespace nx {
LightSampler::LightSampler(const RenderScene& scene) : scene_(&scene) {
  sphereLight_.assign(scene.spheres.size(), -1);
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    if (scene.spheres[i].emission < 0) continue;
    sphereLight_[i] = static_cast<int32_t>(lights_.size());
    lights_.push_back({false, static_cast<uint32_t>(i)});
  }
  for (size_t i = 0; i < scene.pointLights.size(); ++i)
    lights_.push_back({true, static_cast<uint32_t>(i)});
}

bool LightSampler::sample(const Vec3& p, float uChoice, Sample2 u, const SampledWavelengths& lambda,
                          LightSample& out) const {
  if (lights_.empty()) return false;
  const int n = count();
  const int k = std::min(static_cast<int>(uChoice * static_cast<float>(n)), n - 1);
  const Light& light = lights_[static_cast<size_t>(k)];
  const float choice = 1.0f / static_cast<float>(n);
  if (light.point) {
    const PointLight& pl = scene_->pointLights[light.index];
    const Vec3 toLight = pl.position - p;
    const float d2 = dot(toLight, toLight);
    if (!(d2 > 0)) return false;
    out.distance = std::sqrt(d2);
    out.wi = toLight / out.distance;
    out.radiance = evaluate(pl.intensity, lambda) * (1.0f / d2);
    out.pdf = choice;
    out.delta = true;
    out.sphere = GeometryScene::kNoSphere;
    return true;
  }
  const SphereShape& s = scene_->geometry->spheres()[light.index];
  const Vec3d axis = s.center - Vec3d(p);
  const double d2 = dot(axis, axis);
  const double r2 = s.radius * s.radius;
  Vec3 wi;
  double pdf, dist;
  if (d2 <= r2) {
    wi = sampleUniformSphere(u); // inside: every direction meets the sphere
    pdf = 1.0 / (4 * kPi);
    const auto t = intersectSphere(s, Vec3d(p), Vec3d(wi), 0.0, INFINITY);
    dist = t ? *t : 0.0;
  } else {
    // Few dependent divisions and square roots: they are most of this function's time.
    const double d = std::sqrt(d2), invD = 1.0 / d;
    const double oneMinusCosMax = oneMinusCosFromSin2(r2 * invD * invD);
    // The frame and the local direction are unit to float rounding, so wi is too (a relative
    // length error of 1e-7 is far inside the shadow ray's shortening).
    wi = Frame::fromNormal(Vec3(axis * invD)).toWorld(sampleUniformCone(u, oneMinusCosMax));
    pdf = uniformConePdf(oneMinusCosMax);
    // Distance to the near side along the sampled theta (law of cosines), in double: the
    // same 1 - cos(theta) as sampleUniformCone. Directions at the silhouette get the tangent
    // distance (the square root is zero up to rounding).
    const double oneMinusCos = u.u * oneMinusCosMax;
    const double sin2 = oneMinusCos * (2.0 - oneMinusCos);
    dist = d * (1.0 - oneMinusCos) - std::sqrt(std::max(0.0, r2 - d2 * sin2));
  }
  if (!(dist > 0) || !std::isfinite(pdf)) return false;
  out.wi = wi;
  out.distance = static_cast<float>(dist);
  out.radiance = evaluate(
      scene_->emission[static_cast<size_t>(scene_->spheres[light.index].emission)], lambda);
  out.pdf = static_cast<float>(pdf) * choice;
  out.delta = false;
  out.sphere = light.index;
  return true;
}

float LightSampler::pdfSphere(const Vec3& p, uint32_t sphereIndex, const Vec3& wi) const {
  if (sphereIndex >= sphereLight_.size() || sphereLight_[sphereIndex] < 0) return 0;
  const SphereShape& s = scene_->geometry->spheres()[sphereIndex];
  const Vec3d axis = s.center - Vec3d(p);
  const double d2 = dot(axis, axis), r2 = s.radius * s.radius;
  const float choice = 1.0f / static_cast<float>(count());
  if (d2 <= r2) return static_cast<float>(1.0 / (4 * kPi)) * choice;
  const double oneMinusCosMax = oneMinusCosFromSin2(r2 / d2);
  if (dot(axis, Vec3d(wi)) / std::sqrt(d2) < 1.0 - oneMinusCosMax) return 0; // outside the cone
  return static_cast<float>(uniformConePdf(oneMinusCosMax)) * choice;
}

} // namespace nx
