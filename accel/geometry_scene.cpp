#include "accel/geometry_scene.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/frame.h"
#include "core/math_util.h"
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

void sphereOccluded(const RTCOccludedFunctionNArguments* args) {
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
                             std::vector<PlaneShape> planes, std::vector<TriangleMesh> meshes)
    : spheres_(std::move(spheres)), planes_(std::move(planes)), meshes_(std::move(meshes)) {
  const int64_t before = device.bytesInUse();
  scene_ = rtcNewScene(device.handle());
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  auto attach = [&](RTCGeometry g, GeometryEntry entry) {
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    if (byGeomId_.size() <= id) byGeomId_.resize(id + 1, {ShapeKind::Sphere, 0});
    byGeomId_[id] = entry;
  };
  if (!spheres_.empty()) {
    RTCGeometry g = rtcNewGeometry(device.handle(), RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(spheres_.size()));
    rtcSetGeometryUserData(g, spheres_.data());
    rtcSetGeometryBoundsFunction(g, sphereBounds, nullptr);
    rtcSetGeometryIntersectFunction(g, sphereIntersect);
    rtcSetGeometryOccludedFunction(g, sphereOccluded);
    attach(g, {ShapeKind::Sphere, 0});
  }
  for (size_t m = 0; m < meshes_.size(); ++m) {
    const TriangleMesh& mesh = meshes_[m];
    RTCGeometry g = rtcNewGeometry(device.handle(), RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree reads the mesh's buffers in place (no copy): they live as long as this scene.
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, mesh.positionData(),
                               0, 3 * sizeof(float), mesh.vertexCount());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indexData(), 0,
                               3 * sizeof(uint32_t), mesh.triangleCount());
    device.throwIfError("mesh buffers");
    attach(g, {ShapeKind::Triangle, static_cast<uint32_t>(m)});
  }
  rtcCommitScene(scene_);
  device.throwIfError("building the scene's BVH");
  embreeBytes_ = static_cast<size_t>(std::max<int64_t>(0, device.bytesInUse() - before));
}

void sphereUv(SurfaceHit& hit) {
  // u = phi / 2 pi around the y axis (from +z towards +x), v = theta / pi from +y.
  const Vec3d n(hit.ng);
  const double phi = std::atan2(n.x, n.z);
  hit.u = static_cast<float>((phi < 0 ? phi + 2 * kPi : phi) / (2 * kPi));
  hit.v = static_cast<float>(std::acos(std::clamp(n.y, -1.0, 1.0)) / kPi);
}

BoundingBox GeometryScene::bounds() const {
  BoundingBox b;
  for (const SphereShape& s : spheres_) {
    b.add(s.center - Vec3d(s.radius, s.radius, s.radius));
    b.add(s.center + Vec3d(s.radius, s.radius, s.radius));
  }
  for (const TriangleMesh& m : meshes_)
    for (uint32_t i = 0; i < m.vertexCount(); ++i) b.add(Vec3d(m.position(i)));
  return b;
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
  uint32_t index = 0, prim = 0;
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
    const GeometryEntry& entry = byGeomId_[rh.hit.geomID];
    kind = entry.kind;
    index = kind == ShapeKind::Sphere ? rh.hit.primID : entry.mesh;
    prim = rh.hit.primID;
    baryU = rh.hit.u;
    baryV = rh.hit.v;
  }
  if (!found) return false;

  hit.t = tBest;
  hit.kind = kind;
  hit.index = index;
  hit.prim = kind == ShapeKind::Triangle ? prim : 0;
  if (kind == ShapeKind::Sphere) {
    // Re-project onto the surface in double precision: the point is then as accurate as the
    // float it is stored in, whatever the sphere's size.
    const SphereShape& s = spheres_[index];
    const Vec3d n = normalize(o + d * static_cast<double>(tBest) - s.center);
    hit.p = Vec3(s.center + n * s.radius);
    hit.ng = Vec3(n);
    hit.ns = hit.ng;
    hit.u = hit.v = 0; // sphereUv() computes them when a texture needs them
    hit.dpdu = Vec3(Vec3d(n.z, 0, -n.x) * (2 * kPi * s.radius));
    hit.pError = roundingError(hit.p);
  } else if (kind == ShapeKind::Plane) {
    const PlaneShape& pl = planes_[index];
    const Vec3d q = o + d * static_cast<double>(tBest);
    hit.p = Vec3(q - pl.normal * (dot(pl.normal, q) - pl.distance)); // exactly onto the plane
    hit.ng = hit.ns = ng;
    hit.u = hit.v = 0;
    hit.dpdu = Frame::fromNormal(ng).s;
    hit.pError = roundingError(hit.p);
  } else {
    fillMeshHit(baryU, baryV, ng, hit);
  }
  if (!isFinite(hit.p) || !isFinite(hit.ng)) {
    assert(!"a non-finite hit left the intersector"); // debug builds stop here
    nonFinite_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  return true;
}

void GeometryScene::fillMeshHit(float baryU, float baryV, const Vec3& ngEmbree,
                                SurfaceHit& hit) const {
  const TriangleMesh& mesh = meshes_[hit.index];
  const uint32_t* idx = mesh.triangle(hit.prim);
  const TriangleShape tr = mesh.corners(hit.prim);
  // Barycentric interpolation in double from Embree's (u, v): the error is that of u and v
  // (a few float ULPs of the edges) plus the final rounding (pbrt-v4 6.8.5).
  const double u = baryU, v = baryV, w = 1.0 - u - v;
  hit.p = Vec3(tr.a * w + tr.b * u + tr.c * v);
  const Vec3d spread(std::abs(w * tr.a.x) + std::abs(u * tr.b.x) + std::abs(v * tr.c.x),
                     std::abs(w * tr.a.y) + std::abs(u * tr.b.y) + std::abs(v * tr.c.y),
                     std::abs(w * tr.a.z) + std::abs(u * tr.b.z) + std::abs(v * tr.c.z));
  hit.pError = Vec3(spread * static_cast<double>(floatGamma(7)));
  hit.ng = normalize(ngEmbree);
  // Surface coordinates: the mesh's uv, or the barycentrics mapped to (0,0), (1,0), (1,1).
  float uv[3][2] = {{0, 0}, {1, 0}, {1, 1}};
  if (mesh.hasUv())
    for (int k = 0; k < 3; ++k) mesh.uv(idx[k], uv[k][0], uv[k][1]);
  hit.u = static_cast<float>(w * uv[0][0] + u * uv[1][0] + v * uv[2][0]);
  hit.v = static_cast<float>(w * uv[0][1] + u * uv[1][1] + v * uv[2][1]);
  // dp/du from the uv differences (pbrt-v4 6.5.3); a degenerate uv map gets any tangent.
  const double du02 = uv[0][0] - uv[2][0], du12 = uv[1][0] - uv[2][0];
  const double dv02 = uv[0][1] - uv[2][1], dv12 = uv[1][1] - uv[2][1];
  const double det = du02 * dv12 - dv02 * du12;
  const Vec3d dp02 = tr.a - tr.c, dp12 = tr.b - tr.c;
  const Vec3d dpdu = (dp02 * dv12 - dp12 * dv02) * (1.0 / det);
  hit.dpdu = std::abs(det) > 1e-12 && isFinite(Vec3(dpdu)) && length(cross(dpdu, Vec3d(hit.ng))) > 0
                 ? Vec3(dpdu)
                 : Frame::fromNormal(hit.ng).s;
  hit.ns = hit.ng;
  if (mesh.hasNormals()) {
    const Vec3 n = mesh.normal(idx[0]) * static_cast<float>(w) +
                   mesh.normal(idx[1]) * static_cast<float>(u) +
                   mesh.normal(idx[2]) * static_cast<float>(v);
    const float len = length(n);
    // The shading normal lies on the geometric normal's side (pbrt-v4's convention), so that
    // both describe the same surface side.
    if (len > 0 && std::isfinite(len)) hit.ns = dot(n, hit.ng) < 0 ? -(n / len) : n / len;
  }
}

bool GeometryScene::occluded(const Ray& ray) const {
  const Vec3d o(ray.o), d(ray.d);
  bool blocked = false;
  for (const auto& p : planes_) {
    const double t = planeDistance(p, o, d);
    blocked |= t > ray.tMin && t < ray.tMax;
  }
  if (blocked) return true;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = toEmbree(ray);
  rtcOccluded1(scene_, &context, &r);
  return r.tfar == -std::numeric_limits<float>::infinity();
}

} // namespace nx
