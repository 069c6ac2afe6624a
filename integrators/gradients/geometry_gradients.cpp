#include "integrators/gradients/geometry_gradients.h"

#include "accel/shapes.h"

namespace nx {
namespace {

// A scratch list per thread (the walk allocates nothing per vertex once it has grown).
std::vector<SurfaceSlot>& surfaceScratch() {
  thread_local std::vector<SurfaceSlot> list;
  return list;
}

} // namespace

void surfaceSlots(const ShapeTangents& shapes, const GeometryScene& geometry, const SurfaceHit& hit,
                  std::vector<SurfaceSlot>& out) {
  out.clear();
  if (hit.kind == ShapeKind::Sphere && hit.index < shapes.spheres.size()) {
    for (const SphereMotion& m : shapes.spheres[hit.index])
      out.push_back({m.slot, Vec3(m.dCenter) + hit.ng * static_cast<float>(m.dRadius), Vec3()});
    return;
  }
  if (hit.kind != ShapeKind::Triangle || hit.index >= shapes.meshes.size()) return;
  const MeshMotion& mm = shapes.meshes[hit.index];
  if (mm.firstSlot < 0) return;
  const TriangleMesh& mesh = geometry.meshes()[hit.index];
  const uint32_t* idx = mesh.triangle(hit.prim);
  const Vec3 a = mesh.position(idx[0]), e1 = mesh.position(idx[1]) - a,
             e2 = mesh.position(idx[2]) - a;
  const Vec3 N = cross(e1, e2);
  const float len = length(N), inv = 1 / dot(N, N);
  if (!(len > 0)) return;
  const Vec3 x = hit.p - a;
  const float b1 = dot(cross(x, e2), N) * inv, b2 = dot(cross(e1, x), N) * inv;
  const float bary[3] = {1 - b1 - b2, b1, b2};
  const Vec3 nUnit = N / len;
  const float sign = dot(hit.ng, N) < 0 ? -1.0f : 1.0f;
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k) {
      const Vec3 u(mm.linear[k]);
      const Vec3 dN = j == 0   ? cross(u * -1.0f, e2) + cross(e1, u * -1.0f)
                      : j == 1 ? cross(u, e2)
                               : cross(e1, u);
      out.push_back(
          {mm.slot(idx[j], k), u * bary[j], (dN - nUnit * dot(nUnit, dN)) * (sign / len)});
    }
}

namespace {

// d n / d x applied to dx at a hit (the shape's curvature): a sphere's (I - n n^T) dx / r, a
// cylinder side's the same across its axis, a mesh's interpolated normals' through the
// barycentrics; flat shapes turn nothing.
Vec3 normalTurning(const GeometryScene& geometry, const SurfaceHit& hit, const Vec3& dx) {
  const Vec3& n = hit.ns;
  switch (hit.kind) {
  case ShapeKind::Sphere: {
    const double r = geometry.spheres()[hit.index].radius;
    return (dx - hit.ng * dot(hit.ng, dx)) * static_cast<float>(1 / r);
  }
  case ShapeKind::Cylinder: {
    if (hit.prim != static_cast<uint32_t>(CylinderPart::Side)) return {};
    const CylinderShape& c = geometry.cylinders()[hit.index];
    const Vec3 a(c.axis());
    const Vec3 across = dx - a * dot(a, dx);
    return (across - hit.ng * dot(hit.ng, across)) * static_cast<float>(1 / c.radius);
  }
  case ShapeKind::Triangle: {
    const TriangleMesh& mesh = geometry.meshes()[hit.index];
    if (!mesh.hasNormals()) return {};
    const uint32_t* idx = mesh.triangle(hit.prim);
    const Vec3 a = mesh.position(idx[0]), e1 = mesh.position(idx[1]) - a,
               e2 = mesh.position(idx[2]) - a;
    const Vec3 N = cross(e1, e2);
    const float inv = 1 / dot(N, N);
    // x - a = u e1 + v e2: u = ((x - a) x e2) . N / |N|^2, v = (e1 x (x - a)) . N / |N|^2.
    const float du = dot(cross(dx, e2), N) * inv, dv = dot(cross(e1, dx), N) * inv;
    const Vec3 dRaw =
        mesh.normal(idx[0]) * (-du - dv) + mesh.normal(idx[1]) * du + mesh.normal(idx[2]) * dv;
    // hit.ns = +-normalize(raw), raw at the hit's barycentrics
    const Vec3 x = hit.p - a;
    const float bu = dot(cross(x, e2), N) * inv, bv = dot(cross(e1, x), N) * inv;
    const Vec3 raw =
        mesh.normal(idx[0]) * (1 - bu - bv) + mesh.normal(idx[1]) * bu + mesh.normal(idx[2]) * bv;
    const float len = length(raw);
    if (!(len > 0)) return {};
    const float sign = dot(raw, n) < 0 ? -1.0f : 1.0f;
    return (dRaw - n * dot(n, dRaw)) * (sign / len);
  }
  default:
    return {};
  }
}

} // namespace

void vertexMotion(const ShapeTangents& shapes, const GeometryScene& geometry, const Ray& ray,
                  const std::vector<RayMotion>& rayMotion, const SurfaceHit& hit,
                  std::vector<VertexMotion>& out) {
  out.clear();
  const Vec3& n = hit.ng;
  const Vec3& d = ray.d;
  const float t = length(hit.p - ray.o);
  const float nd = dot(n, d);
  if (!(std::abs(nd) > 0)) return; // grazing: the hit's motion is unbounded
  std::vector<SurfaceSlot>& surface = surfaceScratch();
  surfaceSlots(shapes, geometry, hit, surface);
  const bool flat = hit.ns == hit.ng;
  // The point moves with the ray's origin and direction, and along the ray until it is back on
  // the surface (its material point moving at v): n . (dx - v) = 0 with dx = do + t dd + dt d.
  // Its normal turns by the curvature applied to its motion relative to the material point,
  // and with the surface's own turning there (a mesh's face as its vertices move); a mesh's
  // interpolated normals are data and only slide.
  auto add = [&](uint32_t slot, const Vec3& dOrigin, const Vec3& dDir, const SurfaceSlot& s) {
    const Vec3 along = dOrigin + dDir * t;
    VertexMotion m;
    m.slot = slot;
    m.dp = along + d * (dot(n, s.v - along) / nd);
    const Vec3 turn = normalTurning(geometry, hit, m.dp - s.v);
    m.dng = (hit.kind == ShapeKind::Triangle ? Vec3() : turn) + s.dn;
    m.dns = flat ? m.dng : turn;
    m.dDir = dDir;
    out.push_back(m);
  };
  auto own = [&](uint32_t slot) {
    for (const SurfaceSlot& s : surface)
      if (s.slot == slot) return s;
    return SurfaceSlot{slot, {}, {}};
  };
  for (const RayMotion& r : rayMotion) add(r.slot, r.dOrigin, r.dDir, own(r.slot));
  for (const SurfaceSlot& s : surface) {
    bool carried = false;
    for (const RayMotion& r : rayMotion) carried = carried || r.slot == s.slot;
    if (!carried) add(s.slot, Vec3(), Vec3(), s);
  }
}

} // namespace nx
