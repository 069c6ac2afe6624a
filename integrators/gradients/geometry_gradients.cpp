#include "integrators/gradients/geometry_gradients.h"

#include "accel/shapes.h"

namespace nx {
namespace {

// The velocity of the point of sphere k at unit normal n under `slot` (x = c + r n: dc + dr n),
// or false when the slot does not move the sphere.
bool sphereVelocity(const ShapeTangents& shapes, uint32_t k, uint32_t slot, const Vec3& n,
                    Vec3& v) {
  if (k >= shapes.spheres.size()) return false;
  for (const SphereMotion& m : shapes.spheres[k])
    if (m.slot == slot) {
      v = Vec3(m.dCenter) + n * static_cast<float>(m.dRadius);
      return true;
    }
  return false;
}

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
  const bool sphere = hit.kind == ShapeKind::Sphere;
  // The point moves with the ray's origin and direction, and along the ray until it is back on
  // the surface (moving at v): n . (dx - v) = 0 with dx = do + t dd + dt d. Its normal turns by
  // the curvature applied to its motion relative to the surface's material point.
  auto add = [&](uint32_t slot, const Vec3& dOrigin, const Vec3& dDir, const Vec3& v) {
    const Vec3 along = dOrigin + dDir * t;
    VertexMotion m;
    m.slot = slot;
    m.dp = along + d * (dot(n, v - along) / nd);
    m.dns = normalTurning(geometry, hit, m.dp - v);
    // a mesh's face normal stays (its vertices do not move); other shapes' is their normal
    m.dng = hit.kind == ShapeKind::Triangle ? Vec3() : m.dns;
    m.dDir = dDir;
    out.push_back(m);
  };
  for (const RayMotion& r : rayMotion) {
    Vec3 v;
    if (!sphere || !sphereVelocity(shapes, hit.index, r.slot, n, v)) v = Vec3();
    add(r.slot, r.dOrigin, r.dDir, v);
  }
  if (sphere && hit.index < shapes.spheres.size())
    for (const SphereMotion& s : shapes.spheres[hit.index]) {
      bool carried = false;
      for (const RayMotion& r : rayMotion) carried = carried || r.slot == s.slot;
      if (!carried)
        add(s.slot, Vec3(), Vec3(), Vec3(s.dCenter) + n * static_cast<float>(s.dRadius));
    }
}

} // namespace nx
