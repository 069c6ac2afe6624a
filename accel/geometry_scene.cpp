#include "accel/geometry_scene.h"

#include <cassert>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/ray_offset.h"

namespace nx {
namespace {

float roundDown(double v) {
  const float f = static_cast<float>(v);
  return static_cast<double>(f) > v ? std::nextafter(f, -INFINITY) : f;
}
float roundUp(double v) {
  const float f = static_cast<float>(v);
  return static_cast<double>(f) < v ? std::nextafter(f, INFINITY) : f;
}

void sphereBounds(const RTCBoundsFunctionArguments* args) {
  const auto& s = static_cast<const SphereShape*>(args->geometryUserPtr)[args->primID];
  RTCBounds* b = args->bounds_o;
  b->lower_x = roundDown(s.center.x - s.radius);
  b->lower_y = roundDown(s.center.y - s.radius);
  b->lower_z = roundDown(s.center.z - s.radius);
  b->upper_x = roundUp(s.center.x + s.radius);
  b->upper_y = roundUp(s.center.y + s.radius);
  b->upper_z = roundUp(s.center.z + s.radius);
}

// Embree's user-geometry contract: honour the valid mask, accept only tnear < t < tfar,
// shorten tfar and fill the hit on success.
void sphereIntersect(const RTCIntersectFunctionNArguments* args) {
  const auto& s = static_cast<const SphereShape*>(args->geometryUserPtr)[args->primID];
  const unsigned n = args->N;
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, n);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, n);
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3d o(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i));
    const Vec3d d(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i));
    const float tnear = RTCRayN_tnear(ray, n, i);
    float& tfar = RTCRayN_tfar(ray, n, i);
    const auto t = intersectSphere(s, o, d, tnear, tfar);
    if (!t) continue;
    const float tf = static_cast<float>(*t);
    if (!(tf > tnear && tf < tfar)) continue; // lost to float rounding at the interval ends
    const Vec3d ng = (o + d * *t) - s.center;
    tfar = tf;
    RTCHitN_Ng_x(hit, n, i) = static_cast<float>(ng.x);
    RTCHitN_Ng_y(hit, n, i) = static_cast<float>(ng.y);
    RTCHitN_Ng_z(hit, n, i) = static_cast<float>(ng.z);
    RTCHitN_u(hit, n, i) = 0;
    RTCHitN_v(hit, n, i) = 0;
    RTCHitN_primID(hit, n, i) = args->primID;
    RTCHitN_geomID(hit, n, i) = args->geomID;
    RTCHitN_instID(hit, n, i, 0) = args->context->instID[0];
  }
}

// Embree's intersection context extended with the sphere an occlusion query skips (the
// context pointer reaches the callbacks unchanged).
struct OcclusionContext {
  RTCIntersectContext embree;
  uint32_t ignoredSphere;
};

void sphereOccluded(const RTCOccludedFunctionNArguments* args) {
  if (reinterpret_cast<const OcclusionContext*>(args->context)->ignoredSphere == args->primID)
    return;
  const auto& s = static_cast<const SphereShape*>(args->geometryUserPtr)[args->primID];
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3d o(RTCRayN_org_x(args->ray, n, i), RTCRayN_org_y(args->ray, n, i),
                  RTCRayN_org_z(args->ray, n, i));
    const Vec3d d(RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i),
                  RTCRayN_dir_z(args->ray, n, i));
    float& tfar = RTCRayN_tfar(args->ray, n, i);
    if (intersectSphere(s, o, d, RTCRayN_tnear(args->ray, n, i), tfar))
      tfar = -std::numeric_limits<float>::infinity();
  }
}

RTCRay toEmbree(const Ray& r) {
  RTCRay e;
  e.org_x = r.o.x, e.org_y = r.o.y, e.org_z = r.o.z;
  e.dir_x = r.d.x, e.dir_y = r.d.y, e.dir_z = r.d.z;
  e.tnear = r.tMin;
  e.tfar = r.tMax;
  e.time = 0;
  e.mask = 0xFFFFFFFFu;
  e.id = 0;
  e.flags = 0;
  return e;
}

} // namespace

GeometryScene::GeometryScene(EmbreeDevice& device, std::vector<SphereShape> spheres,
                             std::vector<PlaneShape> planes, std::vector<TriangleShape> triangles)
    : spheres_(std::move(spheres)), planes_(std::move(planes)), triangles_(std::move(triangles)) {
  scene_ = rtcNewScene(device.handle());
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  if (!spheres_.empty()) {
    RTCGeometry g = rtcNewGeometry(device.handle(), RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(spheres_.size()));
    rtcSetGeometryUserData(g, spheres_.data());
    rtcSetGeometryBoundsFunction(g, sphereBounds, nullptr);
    rtcSetGeometryIntersectFunction(g, sphereIntersect);
    rtcSetGeometryOccludedFunction(g, sphereOccluded);
    rtcCommitGeometry(g);
    sphereGeomId_ = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
  }
  if (!triangles_.empty()) {
    RTCGeometry g = rtcNewGeometry(device.handle(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * triangles_.size()));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles_.size()));
    if (!v || !idx) device.throwIfError("triangle buffers");
    for (size_t t = 0; t < triangles_.size(); ++t) {
      const Vec3d* corners[3] = {&triangles_[t].a, &triangles_[t].b, &triangles_[t].c};
      for (int k = 0; k < 3; ++k) {
        v[9 * t + 3 * k + 0] = static_cast<float>(corners[k]->x);
        v[9 * t + 3 * k + 1] = static_cast<float>(corners[k]->y);
        v[9 * t + 3 * k + 2] = static_cast<float>(corners[k]->z);
        idx[3 * t + k] = static_cast<unsigned>(3 * t + k);
      }
    }
    rtcCommitGeometry(g);
    triangleGeomId_ = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene_);
  device.throwIfError("building the scene's BVH");
}

GeometryScene::~GeometryScene() {
  rtcReleaseScene(scene_);
}

bool GeometryScene::intersect(const Ray& ray, SurfaceHit& hit) const {
  // Planes first: their nearest hit bounds the BVH query, which then culls more.
  const Vec3d o(ray.o), d(ray.d);
  float tBest = ray.tMax;
  bool found = false;
  ShapeKind kind = ShapeKind::Plane;
  uint32_t index = 0;
  Vec3 ng;
  // Without branches on the outcome (a plane is hit by about half of all rays, which no
  // predictor can guess) and with the divisions independent of each other.
  for (size_t i = 0; i < planes_.size(); ++i) {
    const float tf = static_cast<float>(planeDistance(planes_[i], o, d));
    const bool nearer = tf > ray.tMin && tf < tBest; // false for NaN (ray in the plane)
    found |= nearer;
    tBest = nearer ? tf : tBest;
    index = nearer ? static_cast<uint32_t>(i) : index;
  }
  if (found) ng = Vec3(planes_[index].normal);

  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray = toEmbree(ray);
  rh.ray.tfar = tBest;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rh);
  float baryU = 0, baryV = 0;
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
    found = true;
    tBest = rh.ray.tfar;
    ng = Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    kind = rh.hit.geomID == triangleGeomId_ ? ShapeKind::Triangle : ShapeKind::Sphere;
    index = rh.hit.primID;
    baryU = rh.hit.u;
    baryV = rh.hit.v;
  }
  if (!found) return false;

  hit.t = tBest;
  hit.kind = kind;
  hit.index = index;
  if (kind == ShapeKind::Sphere) {
    // Re-project onto the surface in double precision: the point is then as accurate as the
    // float it is stored in, whatever the sphere's size.
    const SphereShape& s = spheres_[index];
    const Vec3d n = normalize(o + d * static_cast<double>(tBest) - s.center);
    hit.p = Vec3(s.center + n * s.radius);
    hit.ng = Vec3(n);
  } else if (kind == ShapeKind::Plane) {
    const PlaneShape& pl = planes_[index];
    const Vec3d q = o + d * static_cast<double>(tBest);
    hit.p = Vec3(q - pl.normal * (dot(pl.normal, q) - pl.distance)); // exactly onto the plane
    hit.ng = ng;
  } else {
    // Barycentric interpolation in double from Embree's (u, v): the error is that of u and v
    // (a few float ULPs of the edges) plus the final rounding (pbrt-v4 6.8.5).
    const TriangleShape& tr = triangles_[index];
    const double u = baryU, v = baryV, w = 1.0 - u - v;
    const Vec3d q = tr.a * w + tr.b * u + tr.c * v;
    hit.p = Vec3(q);
    const Vec3d spread(std::abs(w * tr.a.x) + std::abs(u * tr.b.x) + std::abs(v * tr.c.x),
                       std::abs(w * tr.a.y) + std::abs(u * tr.b.y) + std::abs(v * tr.c.y),
                       std::abs(w * tr.a.z) + std::abs(u * tr.b.z) + std::abs(v * tr.c.z));
    hit.pError = Vec3(spread * static_cast<double>(floatGamma(7)));
    hit.ng = normalize(ng);
  }
  if (kind != ShapeKind::Triangle) hit.pError = roundingError(hit.p);
  if (!isFinite(hit.p) || !isFinite(hit.ng)) {
    assert(!"a non-finite hit left the intersector"); // debug builds stop here
    nonFinite_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  return true;
}

bool GeometryScene::occluded(const Ray& ray, uint32_t ignoredSphere) const {
  const Vec3d o(ray.o), d(ray.d);
  bool blocked = false;
  for (const auto& p : planes_) {
    const double t = planeDistance(p, o, d);
    blocked |= t > ray.tMin && t < ray.tMax;
  }
  if (blocked) return true;
  OcclusionContext context;
  rtcInitIntersectContext(&context.embree);
  context.ignoredSphere = ignoredSphere;
  RTCRay r = toEmbree(ray);
  rtcOccluded1(scene_, &context.embree, &r);
  return r.tfar == -std::numeric_limits<float>::infinity();
}

} // namespace nx
