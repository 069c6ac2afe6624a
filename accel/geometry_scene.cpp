#include "accel/geometry_scene.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

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

template <class Shape>
void analyticBounds(const RTCBoundsFunctionArguments* args) {
  const auto& s = static_cast<const Shape*>(args->geometryUserPtr)[args->primID];
  const BoundingBox box = s.bounds();
  const Vec3d &lo = box.lo, &hi = box.hi;
  RTCBounds* b = args->bounds_o;
  b->lower_x = roundDown(lo.x), b->lower_y = roundDown(lo.y), b->lower_z = roundDown(lo.z);
  b->upper_x = roundUp(hi.x), b->upper_y = roundUp(hi.y), b->upper_z = roundUp(hi.z);
}

// Embree's user-geometry contract: honour the valid mask, accept only tnear < t < tfar,
// shorten tfar and fill the hit on success (the surface itself is filled in afterwards, in
// double precision; u carries the part).
template <class Shape>
void analyticIntersect(const RTCIntersectFunctionNArguments* args) {
  const auto& s = static_cast<const Shape*>(args->geometryUserPtr)[args->primID];
  const unsigned n = args->N;
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, n);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, n);
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3d o(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i));
    const Vec3d d(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i));
    const float tnear = RTCRayN_tnear(ray, n, i);
    float& tfar = RTCRayN_tfar(ray, n, i);
    const auto h = s.intersect(o, d, tnear, tfar);
    if (!h) continue;
    const float tf = static_cast<float>(h->t);
    if (!(tf > tnear && tf < tfar)) continue; // lost to float rounding at the interval ends
    tfar = tf;
    RTCHitN_Ng_x(hit, n, i) = 0;
    RTCHitN_Ng_y(hit, n, i) = 0;
    RTCHitN_Ng_z(hit, n, i) = 1;
    RTCHitN_u(hit, n, i) = static_cast<float>(h->part);
    RTCHitN_v(hit, n, i) = 0;
    RTCHitN_primID(hit, n, i) = args->primID;
    RTCHitN_geomID(hit, n, i) = args->geomID;
    RTCHitN_instID(hit, n, i, 0) = args->context->instID[0];
  }
}

template <class Shape>
void analyticOccluded(const RTCOccludedFunctionNArguments* args) {
  const auto& s = static_cast<const Shape*>(args->geometryUserPtr)[args->primID];
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3d o(RTCRayN_org_x(args->ray, n, i), RTCRayN_org_y(args->ray, n, i),
                  RTCRayN_org_z(args->ray, n, i));
    const Vec3d d(RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i),
                  RTCRayN_dir_z(args->ray, n, i));
    float& tfar = RTCRayN_tfar(args->ray, n, i);
    if (s.intersect(o, d, RTCRayN_tnear(args->ray, n, i), tfar))
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
    : GeometryScene(
          device,
          [&] {
            AnalyticShapes a;
            std::get<std::vector<SphereShape>>(a) = std::move(spheres);
            return a;
          }(),
          std::move(planes), std::move(meshes)) {}

GeometryScene::GeometryScene(EmbreeDevice& device, AnalyticShapes analytic,
                             std::vector<PlaneShape> planes, std::vector<TriangleMesh> meshes)
    : analytic_(std::move(analytic)), planes_(std::move(planes)), meshes_(std::move(meshes)) {
  const int64_t before = device.bytesInUse();
  scene_ = rtcNewScene(device.handle());
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  auto attach = [&](RTCGeometry g, GeometryEntry entry) {
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    if (byGeomId_.size() <= id) byGeomId_.resize(id + 1, {ShapeKind::Plane, 0});
    byGeomId_[id] = entry;
  };
  // One user geometry per analytic kind (its shapes are its primitives).
  forEachAnalyticKind([&]<class Shape>() {
    std::vector<Shape>& shapes = std::get<std::vector<Shape>>(analytic_);
    if (shapes.empty()) return;
    RTCGeometry g = rtcNewGeometry(device.handle(), RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(shapes.size()));
    rtcSetGeometryUserData(g, shapes.data());
    rtcSetGeometryBoundsFunction(g, analyticBounds<Shape>, nullptr);
    rtcSetGeometryIntersectFunction(g, analyticIntersect<Shape>);
    rtcSetGeometryOccludedFunction(g, analyticOccluded<Shape>);
    attach(g, {kShapeKindOf<Shape>, 0});
  });
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

BoundingBox GeometryScene::bounds() const {
  BoundingBox b;
  forEachAnalyticKind([&]<class Shape>() {
    for (const Shape& s : primitives<Shape>()) b.add(s.bounds());
  });
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
    index = kind == ShapeKind::Triangle ? entry.mesh : rh.hit.primID;
    prim = rh.hit.primID;
    baryU = rh.hit.u;
    baryV = rh.hit.v;
  }
  if (!found) return false;

  hit.t = tBest;
  hit.kind = kind;
  hit.index = index;
  hit.uvPending = false;
  if (kind == ShapeKind::Triangle) {
    hit.prim = prim;
    fillMeshHit(baryU, baryV, ng, hit);
  } else if (kind == ShapeKind::Plane) {
    hit.prim = 0;
    const PlaneShape& pl = planes_[index];
    const Vec3d q = o + d * static_cast<double>(tBest);
    hit.p = Vec3(q - pl.normal * (dot(pl.normal, q) - pl.distance)); // exactly onto the plane
    hit.ng = hit.ns = ng;
    hit.u = hit.v = 0;
    hit.dpdu = Frame::fromNormal(ng).s;
    hit.pError = roundingError(hit.p);
  } else {
    // An analytic primitive: Embree's u carries its part (analyticIntersect).
    hit.prim = static_cast<uint32_t>(baryU);
    visitPrimitive(kind, index, [&](const auto& shape) {
      shape.fillHit(o, d, static_cast<double>(tBest), hit.prim, hit);
    });
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
