#include "integrators/gradients/geometry_gradients.h"

#include <array>

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
  if (isAnalytic(hit.kind)) {
    // The primitive's own motion of the material point at the hit and of its normal.
    visitAnalyticKind(hit.kind, [&]<class P>() {
      const auto& motions = shapes.motions<P>();
      if (hit.index >= motions.size()) return;
      const P& base = geometry.primitives<P>()[hit.index];
      for (const PrimitiveMotion<P>& m : motions[hit.index]) {
        Vec3d v, dn;
        m.at(base, Vec3d(hit.p), hit.prim, v, dn);
        out.push_back({m.slot, Vec3(v), Vec3(dn), Vec3(dn)});
      }
    });
    return;
  }
  if (hit.kind != ShapeKind::Triangle || hit.index >= shapes.meshes.size()) return;
  const MeshMotion& mm = shapes.meshes[hit.index];
  if (!mm.moves()) return;
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
  // Each slot's velocities of the triangle's three vertices: a vertex's own coordinates move
  // one of them, the transform's entries all three, a quad's or a triangle's corners some (at
  // most 9 + 12 + 9 slots, no allocation).
  struct Moving {
    uint32_t slot;
    Vec3 u[3];
    Vec3 dns;
  };
  std::array<Moving, 30> moving;
  size_t count = 0;
  auto entry = [&](uint32_t slot) -> Moving& {
    for (size_t i = 0; i < count; ++i)
      if (moving[i].slot == slot) return moving[i];
    moving[count] = {slot, {}, {}};
    return moving[count++];
  };
  for (int j = 0; j < 3; ++j)
    mm.forEachVelocity(idx[j], [&](uint32_t slot, const Vec3d& u) { entry(slot).u[j] = Vec3(u); });
  if (mesh.hasNormals()) {
    // The transform turns the vertex normals too: n_j = M^-T l_j / |M^-T l_j|, so entry (r, c)
    // of M turns it by -n_j[r] (I - n_j n_j^T) q_c, q_c row c of M^-1; the shading normal
    // +-normalize(sum_j b_j n_j) turns with them.
    const Vec3 n[3] = {mesh.normal(idx[0]), mesh.normal(idx[1]), mesh.normal(idx[2])};
    const Vec3 raw = n[0] * bary[0] + n[1] * bary[1] + n[2] * bary[2];
    const float rawLength = length(raw);
    const float shadingSign = dot(raw, hit.ns) < 0 ? -1.0f : 1.0f;
    if (rawLength > 0)
      mm.forEachTurningEntry([&](uint32_t slot, int r, int c) {
        const Vec3 q(mm.inverseRows[c]);
        Vec3 dRaw;
        for (int j = 0; j < 3; ++j) dRaw += (q - n[j] * dot(n[j], q)) * (-n[j][r] * bary[j]);
        entry(slot).dns = (dRaw - hit.ns * dot(hit.ns, dRaw)) * (shadingSign / rawLength);
      });
  }
  for (size_t i = 0; i < count; ++i) {
    const Moving& m = moving[i];
    const Vec3 dN = cross(m.u[1] - m.u[0], e2) + cross(e1, m.u[2] - m.u[0]);
    out.push_back({m.slot, m.u[0] * bary[0] + m.u[1] * bary[1] + m.u[2] * bary[2],
                   (dN - nUnit * dot(nUnit, dN)) * (sign / len), m.dns});
  }
}

namespace {

// d n / d x applied to dx at a hit (the shape's curvature): an analytic primitive's own
// (normalTurning in its file), a mesh's interpolated normals' through the barycentrics; planes
// turn nothing.
Vec3 normalTurning(const GeometryScene& geometry, const SurfaceHit& hit, const Vec3& dx) {
  const Vec3& n = hit.ns;
  if (hit.kind == ShapeKind::Plane) return {};
  if (isAnalytic(hit.kind))
    return geometry.visitPrimitive(hit.kind, hit.index,
                                   [&](const auto& shape) { return shape.normalTurning(hit, dx); });
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
    m.dns = flat ? m.dng : turn + s.dns;
    m.dDir = dDir;
    out.push_back(m);
  };
  auto own = [&](uint32_t slot) {
    for (const SurfaceSlot& s : surface)
      if (s.slot == slot) return s;
    return SurfaceSlot{slot, {}, {}, {}};
  };
  for (const RayMotion& r : rayMotion) add(r.slot, r.dOrigin, r.dDir, own(r.slot));
  for (const SurfaceSlot& s : surface) {
    bool carried = false;
    for (const RayMotion& r : rayMotion) carried = carried || r.slot == s.slot;
    if (!carried) add(s.slot, Vec3(), Vec3(), s);
  }
}

} // namespace nx
