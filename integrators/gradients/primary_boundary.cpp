#include "integrators/gradients/primary_boundary.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/math_util.h"
#include "integrators/gradients/geometry_gradients.h"
#include "integrators/gradients/gradient_context.h"
#include "integrators/gradients/mesh_outlines.h"
#include "integrators/render_scene.h"

namespace nx {
namespace {

constexpr uint32_t kBoundarySalt = 0x3c6ef372U;
constexpr int kChunk = 256;          // samples per task (an even number: both replicates)
constexpr double kFilmOffset = 5e-3; // pixels either side of an outline the two paths start
constexpr int64_t kMaxSamplesPerOutline = 1 << 24;
constexpr int64_t kBatch = 64; // chunks sampled at once

Vec3d col(const Matrix3& m, int j) {
  return {m[0][j], m[1][j], m[2][j]};
}

// The pinhole's projection: film position (pixels, as generateRay takes them) of a world
// point, false behind the camera; with the derivative of the film position along dp.
struct Projection {
  const CameraCalibration& c;
  bool project(const Vec3d& p, double& x, double& y) const {
    const Vector3d q = multiply(c.R, {p.x, p.y, p.z});
    const double z = q[2] + c.t.z;
    if (!(z > 0)) return false;
    x = c.fx * (q[0] + c.t.x) / z + c.cx + 0.5;
    y = c.fy * (q[1] + c.t.y) / z + c.cy + 0.5;
    return true;
  }
  void along(const Vec3d& p, const Vec3d& dp, double& dx, double& dy) const {
    const Vector3d q = multiply(c.R, {p.x, p.y, p.z});
    const Vector3d dq = multiply(c.R, {dp.x, dp.y, dp.z});
    const double X = q[0] + c.t.x, Y = q[1] + c.t.y, z = q[2] + c.t.z;
    dx = c.fx * (dq[0] * z - X * dq[2]) / (z * z);
    dy = c.fy * (dq[1] * z - Y * dq[2]) / (z * z);
  }
  // The unnormalised ray direction through film (x, y) and its derivatives along x and y
  // (d = R^T K^-1 (x - 1/2, y - 1/2, 1)).
  Vec3d direction(double x, double y, Vec3d& ddx, Vec3d& ddy) const {
    const Matrix3 Rt = {{{c.R[0][0], c.R[1][0], c.R[2][0]},
                         {c.R[0][1], c.R[1][1], c.R[2][1]},
                         {c.R[0][2], c.R[1][2], c.R[2][2]}}};
    ddx = col(Rt, 0) * (1 / c.fx);
    ddy = col(Rt, 1) * (1 / c.fy);
    return ddx * (x - 0.5 - c.cx) + ddy * (y - 0.5 - c.cy) + col(Rt, 2);
  }
};

// An outline on the film: an analytic primitive's outline seen from the camera (silhouettes
// and rims), the edge of its shadow under a point or spot light on what the camera sees, an
// infinite plane's horizon, or a mesh's outline or shadow's edge.
struct Outline {
  enum class Kind { Silhouette, Shadow, Horizon, MeshSilhouette, MeshShadow };
  Kind kind = Kind::Silhouette;
  ShapeKind primitive =
      ShapeKind::Plane;                  ///< the analytic primitive's kind (a Silhouette or Shadow)
  uint32_t shape = 0;                    ///< the primitive (or the plane, or the mesh)
  Vec3d from;                            ///< the camera's or the light's position
  OutlineCurves curves;                  ///< the primitive's outline seen from `from`
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0; ///< a horizon's segment on the film
  EdgeSet edges; ///< a mesh's silhouette edges seen from `from` (by film or scene length)
  /// A mesh's outline as the camera moves it on the film: its edges are MeshMotion::cameraEdges
  /// and its rates the camera's slots' (else MeshMotion::edges and the slots moving vertices)
  bool camera = false;
};

// The edges a mesh outline chooses from.
const std::vector<MeshEdge>& outlineEdges(const MeshMotion& mm, const Outline& o) {
  return o.camera ? mm.cameraEdges : mm.edges;
}

// An outline of `kind` of shape `shape` seen from `from`.
Outline outlineOf(Outline::Kind kind, uint32_t shape, const Vec3d& from) {
  Outline o;
  o.kind = kind, o.shape = shape, o.from = from;
  return o;
}

// A point of an outline on the film: where (x, y), the unit normal towards phi > 0, |grad phi|,
// the film length per unit of the sampling's first number (so that a sample's share of the
// outline is speed / samples), and how each slot moves phi there.
struct OutlinePoint {
  double x = 0, y = 0, nx = 0, ny = 0, grad = 0, speed = 0;
  std::vector<std::pair<uint32_t, double>> dPhi; ///< (slot, d phi / d slot)
                                                 // adds a slot's rate
  void add(uint32_t slot, double rate) { addRate(dPhi, slot, rate); }
};

// The rates of the camera's slots: phi's change as the ray through the point moves (by its
// origin and unit direction), given phi's derivatives along both.
void cameraRates(const ShapeTangents& shapes, double x, double y, const Vec3d& dPhiDo,
                 const Vec3d& dPhiDd, OutlinePoint& p) {
  for (const CameraMotion& c : shapes.camera) {
    Vec3d dOrigin, dDirection;
    c.ray(x, y, dOrigin, dDirection);
    p.add(c.slot, dot(dPhiDo, dOrigin) + dot(dPhiDd, dDirection));
  }
}

// The rates of the slots moving the outline's primitive at its point m on `part`, ne across
// the outline: d phi / d slot = -ne . v, v the velocity of the material point at m.
void primitiveRates(const IntegratorContext& ctx, const Outline& o, const Vec3d& m, uint32_t part,
                    const Vec3d& ne, OutlinePoint& p) {
  forEachPrimitiveVelocity(ctx.gradients->tangents->shapes, *ctx.scene->geometry, o.primitive,
                           o.shape, m, part,
                           [&](uint32_t slot, const Vec3d& v) { p.add(slot, -dot(ne, v)); });
}

// The point of an outline's curves at (u1, u2): a curve chosen uniformly by u1, its point at
// u2 (false where the curve's point is not of the outline); `count` curves to choose from.
const OutlineCurve* curvePoint(const Outline& o, double u1, double u2, Vec3d& m, Vec3d& dm) {
  const int count = o.curves.count;
  if (count == 0) return nullptr;
  const OutlineCurve& c =
      o.curves.curve[static_cast<size_t>(std::min(count - 1, static_cast<int>(u1 * count)))];
  m = c.at(u2), dm = c.tangent(u2);
  return c.keeps(m) ? &c : nullptr;
}

// An analytic primitive's outline seen from the camera (a silhouette or a rim): phi = ne .
// (y - m), y the camera ray's point at m's distance and ne across the outline (outlineNormal:
// the surface's normal at a silhouette; its sign does not matter, the jump and the rates turn
// together).
bool silhouettePoint(const IntegratorContext& ctx, const Outline& o, double u1, double u2,
                     OutlinePoint& p) {
  Vec3d m, dm;
  const OutlineCurve* curve = curvePoint(o, u1, u2, m, dm);
  if (!curve) return false;
  const Vec3d ne = outlineNormal(o.from, m, dm);
  const RenderScene& scene = *ctx.scene;
  const Projection proj{scene.camera.calibration()};
  if (!proj.project(m, p.x, p.y)) return false;
  double dx, dy;
  proj.along(m, dm, dx, dy);
  p.speed = o.curves.count * std::hypot(dx, dy);
  Vec3d ddx, ddy;
  const Vec3d dir = proj.direction(p.x, p.y, ddx, ddy);
  const double len = length(dir);
  const Vec3d d = dir / len;
  // d phi / d (film x) = t (ne . d d / dx), d d / dx = (I - d d^T) ddx / |dir|, ne . d = 0
  const double t = dot(m - o.from, d);
  const double gx = t * dot(ne, ddx) / len, gy = t * dot(ne, ddy) / len;
  p.grad = std::hypot(gx, gy);
  if (!(p.grad > 0) || !(p.speed > 0)) return false;
  p.nx = gx / p.grad, p.ny = gy / p.grad;
  p.dPhi.clear();
  primitiveRates(ctx, o, m, curve->part, ne, p);
  // the camera: d phi / d o = ne, d phi / d d = t ne
  cameraRates(ctx.gradients->tangents->shapes, p.x, p.y, ne, ne * t, p);
  return true;
}

// True when the camera sees point x itself (nothing nearer on its ray).
bool seenByCamera(const RenderScene& scene, const Vec3d& x, uint64_t& rays) {
  const Vec3d cam = scene.camera.position();
  Ray view;
  view.o = Vec3(cam);
  view.d = Vec3(normalize(x - cam));
  SurfaceHit seen;
  ++rays;
  return scene.geometry->intersect(view, seen) &&
         std::abs(static_cast<double>(seen.t) - length(x - cam)) <= 1e-4 * length(x - cam);
}

// A surface point x (normal n) the camera sees at film position (p.x, p.y): how it moves as
// the camera ray through that film position moves and as its surface moves.
struct SeenPoint {
  Vec3d d, n, ddx, ddy; ///< the ray's unit direction, the normal, the direction's d / d film
  double len = 1, t = 0, nd = 0;
  SeenPoint(const Projection& proj, const OutlinePoint& p, const Vec3d& x, const Vec3d& normal,
            const Vec3d& cam)
      : n(normal) {
    const Vec3d dir = proj.direction(p.x, p.y, ddx, ddy);
    len = length(dir);
    d = dir / len;
    t = length(x - cam);
    nd = dot(n, d);
  }
  /// x's motion at a fixed film position as the camera ray moves (its origin and direction
  /// giving `along`) and the surface at v: dx = along + d n . (v - along) / (n . d).
  Vec3d moved(const Vec3d& along, const Vec3d& v) const {
    return along + d * (dot(n, v - along) / nd);
  }
  /// Sets p's film gradient of phi (|grad|, its unit direction) from d phi / d x; false where
  /// it vanishes or the outline does not move on the film.
  bool filmGradient(const Vec3d& dPhiDx, OutlinePoint& p) const {
    auto perFilm = [&](const Vec3d& dd) { return moved(((dd - d * dot(d, dd)) / len) * t, {}); };
    const double gx = dot(dPhiDx, perFilm(ddx)), gy = dot(dPhiDx, perFilm(ddy));
    p.grad = std::hypot(gx, gy);
    if (!(p.grad > 0) || !(p.speed > 0)) return false;
    p.nx = gx / p.grad, p.ny = gy / p.grad;
    p.dPhi.clear();
    return true;
  }
};

// The rates of the slots moving the surface a shadow falls on (at `hit`), at a fixed film
// position: d phi / d x times x's motion with its surface.
void receiverRates(const IntegratorContext& ctx, const SurfaceHit& hit, const Vec3d& dPhiDx,
                   const SeenPoint& seen, OutlinePoint& p) {
  thread_local std::vector<SurfaceSlot> surface;
  surfaceSlots(ctx.gradients->tangents->shapes, *ctx.scene->geometry, hit, surface);
  for (const SurfaceSlot& s : surface) p.add(s.slot, dot(dPhiDx, seen.moved(Vec3d{}, Vec3d(s.v))));
}

// The rates of the camera's slots at a shadow's edge on a static surface: d phi / d x times the
// seen point's motion as the camera ray through (p.x, p.y) moves.
void seenPointCameraRates(const ShapeTangents& shapes, const Vec3d& dPhiDx, const SeenPoint& seen,
                          OutlinePoint& p) {
  for (const CameraMotion& c : shapes.camera) {
    Vec3d dOrigin, dDirection;
    c.ray(p.x, p.y, dOrigin, dDirection);
    p.add(c.slot, dot(dPhiDx, seen.moved(dOrigin + dDirection * seen.t, {})));
  }
}

// A shadow's edge: the light's ray past the primitive's outline at m goes on to a surface at
// x; phi(y) = ne . (z(y) - m), z the point of the line light -> x(y) at m's distance from the
// light, ne across the outline seen from the light, x(y) what the camera sees at y.
bool shadowPoint(const IntegratorContext& ctx, const Outline& o, double u1, double u2,
                 OutlinePoint& p, uint64_t& rays) {
  Vec3d m, dm;
  const OutlineCurve* curve = curvePoint(o, u1, u2, m, dm);
  if (!curve) return false;
  const Vec3d ne = outlineNormal(o.from, m, dm);
  const RenderScene& scene = *ctx.scene;
  const Projection proj{scene.camera.calibration()};
  const Vec3d cam = scene.camera.position();
  const Vec3d e = normalize(m - o.from);
  // The ray starts at the outline's point and is looked at from 1% of the primitive's size on,
  // where a ray grazing a sphere lies 5e-5 radii outside it (far beyond rounding: a line
  // touching a convex surface does not meet it again, but a rounded one can).
  Ray beyond;
  beyond.o = Vec3(m);
  beyond.d = Vec3(e);
  beyond.tMin = static_cast<float>(1e-2 * curve->size);
  SurfaceHit hit;
  ++rays;
  if (!scene.geometry->intersect(beyond, hit)) return false;
  const Vec3d x(hit.p), n(hit.ng);
  if (!proj.project(x, p.x, p.y)) return false;
  if (!seenByCamera(scene, x, rays)) return false;
  // dx / d s: along the light's ray through m(s), kept on the surface's tangent plane
  const Vec3d lm = m - o.from;
  const double s = dot(n, x - o.from) / dot(n, lm);
  const Vec3d dxA = dm * s + lm * (-s * dot(n, dm) / dot(n, lm));
  double fx, fy;
  proj.along(x, dxA, fx, fy);
  p.speed = o.curves.count * std::hypot(fx, fy);
  // grad_y phi = d phi / d x . d x / d y: d phi / d x = (|m - light| / l) ne (l the light's
  // distance to x), d x / d y_j = t (I - d n^T / (n . d)) d d / d y_j
  const double l = length(x - o.from);
  const Vec3d dPhiDx = ne * (length(lm) / l);
  const SeenPoint seen(proj, p, x, n, cam);
  if (!seen.filmGradient(dPhiDx, p)) return false;
  const ShapeTangents& shapes = ctx.gradients->tangents->shapes;
  primitiveRates(ctx, o, m, curve->part, ne, p);
  receiverRates(ctx, hit, dPhiDx, seen, p); // (a receiver that moves, the primitive's inside too)
  seenPointCameraRates(shapes, dPhiDx, seen, p);
  return true;
}

// An infinite plane's horizon, a straight line on the film: phi = s n . d(y), s making phi < 0
// where the camera's rays meet the plane.
bool horizonPoint(const IntegratorContext& ctx, const Outline& o, double u, OutlinePoint& p) {
  const RenderScene& scene = *ctx.scene;
  const PlaneShape& plane = scene.geometry->planes()[o.shape];
  const Projection proj{scene.camera.calibration()};
  p.x = o.x0 + (o.x1 - o.x0) * u, p.y = o.y0 + (o.y1 - o.y0) * u;
  p.speed = std::hypot(o.x1 - o.x0, o.y1 - o.y0);
  const Vec3d n = normalize(plane.normal);
  const double s = dot(n, scene.camera.position()) > plane.distance ? 1.0 : -1.0;
  Vec3d ddx, ddy;
  const Vec3d dir = proj.direction(p.x, p.y, ddx, ddy);
  const double len = length(dir);
  const Vec3d d = dir / len;
  auto unit = [&](const Vec3d& dd) { return (dd - d * dot(d, dd)) / len; };
  const double gx = s * dot(n, unit(ddx)), gy = s * dot(n, unit(ddy));
  p.grad = std::hypot(gx, gy);
  if (!(p.grad > 0) || !(p.speed > 0)) return false;
  p.nx = gx / p.grad, p.ny = gy / p.grad;
  p.dPhi.clear();
  cameraRates(ctx.gradients->tangents->shapes, p.x, p.y, {}, n * s, p);
  return true;
}

// The rates of the slots moving an edge's vertices: d phi / d v0 and d phi / d v1 (in the
// scene), times each slot's velocity of the vertex.
void edgeRates(const MeshMotion& mm, const MeshEdge& e, const Vec3d& dPhiDv0, const Vec3d& dPhiDv1,
               OutlinePoint& p) {
  mm.forEachVelocity(e.v0, [&](uint32_t slot, const Vec3d& u) { p.add(slot, dot(dPhiDv0, u)); });
  mm.forEachVelocity(e.v1, [&](uint32_t slot, const Vec3d& u) { p.add(slot, dot(dPhiDv1, u)); });
}

// A moving mesh's outline seen from the camera (silhouette edges; every edge seen of a
// flat-shaded mesh): an edge chosen by its length on the film,
// a point uniformly along it there; phi = n_e . d(y), n_e = (v0 - o) x (v1 - o).
bool meshSilhouettePoint(const IntegratorContext& ctx, const Outline& o, double u1, double u2,
                         OutlinePoint& p) {
  const RenderScene& scene = *ctx.scene;
  const TriangleMesh& mesh = scene.geometry->meshes()[o.shape];
  const MeshMotion& mm = ctx.gradients->tangents->shapes.meshes[o.shape];
  const Projection proj{scene.camera.calibration()};
  double share = 0;
  const MeshEdge& e = outlineEdges(mm, o)[o.edges.choose(u1, share)];
  const Vec3d v0(mesh.position(e.v0)), v1(mesh.position(e.v1));
  double x0, y0, x1, y1;
  if (!proj.project(v0, x0, y0) || !proj.project(v1, x1, y1)) return false;
  p.x = x0 + (x1 - x0) * u2, p.y = y0 + (y1 - y0) * u2;
  p.speed = o.edges.total(); // (an edge chosen with probability share / total, then u2)
  Vec3d ddx, ddy;
  const Vec3d dir = proj.direction(p.x, p.y, ddx, ddy);
  const double len = length(dir);
  const Vec3d d = dir / len;
  const Vec3d ne = cross(v0 - o.from, v1 - o.from);
  auto unit = [&](const Vec3d& dd) { return (dd - d * dot(d, dd)) / len; };
  const double gx = dot(ne, unit(ddx)), gy = dot(ne, unit(ddy));
  p.grad = std::hypot(gx, gy);
  if (!(p.grad > 0) || !(share > 0)) return false;
  p.nx = gx / p.grad, p.ny = gy / p.grad;
  p.dPhi.clear();
  if (o.camera) // d phi / d o = d x (v1 - v0), d phi / d d = n_e
    cameraRates(ctx.gradients->tangents->shapes, p.x, p.y, cross(d, v1 - v0), ne, p);
  else // n_e . d = (v0 - o) . ((v1 - o) x d): d / d v0 = (v1 - o) x d, d / d v1 = d x (v0 - o)
    edgeRates(mm, e, cross(v1 - o.from, d), cross(d, v0 - o.from), p);
  return true;
}

// A moving mesh's shadow's edge under a point or spot light: a silhouette edge seen from the
// light chosen by its length, a point uniformly along it; the light's ray through it goes on to
// a surface at x; phi(y) = n_L . (x(y) - light), n_L = (v0 - light) x (v1 - light).
bool meshShadowPoint(const IntegratorContext& ctx, const Outline& o, double u1, double u2,
                     OutlinePoint& p, uint64_t& rays) {
  const RenderScene& scene = *ctx.scene;
  const TriangleMesh& mesh = scene.geometry->meshes()[o.shape];
  const MeshMotion& mm = ctx.gradients->tangents->shapes.meshes[o.shape];
  const Projection proj{scene.camera.calibration()};
  const Vec3d cam = scene.camera.position();
  double share = 0;
  const MeshEdge& e = outlineEdges(mm, o)[o.edges.choose(u1, share)];
  const Vec3d v0(mesh.position(e.v0)), v1(mesh.position(e.v1));
  const Vec3d m = v0 + (v1 - v0) * u2, lm = m - o.from;
  // past the edge (a silhouette edge's triangles lie on one side of the light's ray)
  Ray beyond;
  beyond.o = Vec3(m);
  beyond.d = Vec3(normalize(lm));
  beyond.tMin = static_cast<float>(1e-3 * length(v1 - v0));
  SurfaceHit hit;
  ++rays;
  if (!scene.geometry->intersect(beyond, hit)) return false;
  const Vec3d x(hit.p), n(hit.ng);
  if (!proj.project(x, p.x, p.y)) return false;
  if (!seenByCamera(scene, x, rays)) return false;
  const double s = dot(n, x - o.from) / dot(n, lm);
  const Vec3d dm = v1 - v0, dxS = dm * s + lm * (-s * dot(n, dm) / dot(n, lm));
  double fx, fy;
  proj.along(x, dxS, fx, fy);
  p.speed = std::hypot(fx, fy) * o.edges.total() / share;
  const Vec3d nL = cross(v0 - o.from, v1 - o.from);
  const SeenPoint seen(proj, p, x, n, cam);
  if (!seen.filmGradient(nL, p)) return false;
  if (o.camera) {
    seenPointCameraRates(ctx.gradients->tangents->shapes, nL, seen, p);
    return true;
  }
  // n_L . (x - l) = (v0 - l) . ((v1 - l) x (x - l)): d / d v0 = (v1 - l) x (x - l),
  // d / d v1 = (x - l) x (v0 - l)
  edgeRates(mm, e, cross(v1 - o.from, x - o.from), cross(x - o.from, v0 - o.from), p);
  receiverRates(ctx, hit, nL, seen, p);
  return true;
}

// The point of outline `o` at (u1, u2) in [0, 1)^2, or false where the camera does not see it.
bool outlinePoint(const IntegratorContext& ctx, const Outline& o, double u1, double u2,
                  OutlinePoint& p, uint64_t& rays) {
  switch (o.kind) {
  case Outline::Kind::Silhouette:
    return silhouettePoint(ctx, o, u1, u2, p);
  case Outline::Kind::Shadow:
    return shadowPoint(ctx, o, u1, u2, p, rays);
  case Outline::Kind::Horizon:
    return horizonPoint(ctx, o, u1, p);
  case Outline::Kind::MeshSilhouette:
    return meshSilhouettePoint(ctx, o, u1, u2, p);
  case Outline::Kind::MeshShadow:
    return meshShadowPoint(ctx, o, u1, u2, p, rays);
  }
  return false;
}

// The outline's length on the film in pixels where the camera sees it, estimated on a 16 x 16
// lattice of the sampling's numbers (the mean of speed where seen), what the sample count is
// set from.
double filmLength(const IntegratorContext& ctx, const Outline& o) {
  double total = 0;
  uint64_t rays = 0;
  OutlinePoint p;
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j)
      if (outlinePoint(ctx, o, (i + 0.5) / 16, (j + 0.5) / 16, p, rays)) total += p.speed;
  return total / 256;
}

// The samples [first, first + n) of `count` on outline `o`, appended to `out`.
void sampleOutline(const IntegratorContext& ctx, const PrimaryBoundaryRequest& req,
                   const PixelSequence& sequence, const Outline& o, int64_t first, int64_t n,
                   int64_t count, std::vector<BoundaryContribution>& out, uint64_t& rays) {
  const RenderScene& scene = *ctx.scene;
  TraceCounters counters;
  OutlinePoint p;
  for (int64_t b = first; b < first + n; ++b) {
    PixelSampleStream head(sequence, static_cast<uint32_t>(b));
    const Sample2 u = head.next2D();
    if (!outlinePoint(ctx, o, u.u, u.v, p, counters.rays)) continue;
    // Compared as floats first: a point far outside (or NaN) is never cast to int.
    if (!(p.x >= req.rect.x0 && p.x < req.rect.x1 && p.y >= req.rect.y0 && p.y < req.rect.y1))
      continue;
    const int px = static_cast<int>(std::floor(p.x)), py = static_cast<int>(std::floor(p.y));
    bool moves = false;
    for (const auto& [slot, rate] : p.dPhi) moves = moves || rate != 0;
    if (!moves) continue; // (a static outline, e.g. a static sphere's shadow on a static floor)
    // L where phi < 0 (the sphere seen, or in its shadow) minus L where phi > 0, with the same
    // random numbers, just either side of the outline on the film.
    SampledSpectrum L[2];
    SampledWavelengths lambda;
    for (int side = 0; side < 2; ++side) {
      PixelSampleStream rng(sequence, static_cast<uint32_t>(b));
      rng.next2D(); // the outline's point
      lambda = req.wavelengths(rng);
      const double sign = side == 0 ? -kFilmOffset : kFilmOffset;
      const Ray ray = scene.camera.generateRay(p.x + sign * p.nx, p.y + sign * p.ny);
      L[side] = tracePath(ctx, ray, lambda, rng, counters);
    }
    const SampledSpectrum jump = L[0] + L[1] * -1.0f;
    if (jump.isBlack()) continue;
    // v_n = -(d phi / d theta) / |grad phi|; the sample's share of the outline speed / count
    const double weight = p.speed / static_cast<double>(count) / p.grad;
    for (const auto& [slot, dPhi] : p.dPhi)
      if (dPhi != 0)
        out.push_back(
            {px, py, (b & 1) != 0, slot, lambda, jump * static_cast<float>(-dPhi * weight)});
  }
  rays += counters.rays;
}

// The segment of the line A x + B y + C = 0 inside the rectangle, or false.
bool clipLine(double A, double B, double C, const PixelRect& r, Outline& o) {
  std::vector<std::pair<double, double>> points;
  auto inside = [&](double x, double y) {
    return x >= r.x0 - 1e-9 && x <= r.x1 + 1e-9 && y >= r.y0 - 1e-9 && y <= r.y1 + 1e-9;
  };
  if (B != 0)
    for (double x : {static_cast<double>(r.x0), static_cast<double>(r.x1)})
      if (const double y = -(A * x + C) / B; inside(x, y)) points.push_back({x, y});
  if (A != 0)
    for (double y : {static_cast<double>(r.y0), static_cast<double>(r.y1)})
      if (const double x = -(B * y + C) / A; inside(x, y)) points.push_back({x, y});
  if (points.size() < 2) return false;
  std::sort(points.begin(), points.end());
  o.x0 = points.front().first, o.y0 = points.front().second;
  o.x1 = points.back().first, o.y1 = points.back().second;
  return std::hypot(o.x1 - o.x0, o.y1 - o.y0) > 0;
}

// Mesh k's silhouette seen from the camera and its shadows' edges under `lights`, over its
// moving edges (`camera` false) or, as the camera moves, over all its edges.
void meshOutlines(const RenderScene& scene, const MeshMotion& mm, uint32_t k,
                  const std::vector<Vec3d>& lights, bool camera, std::vector<Outline>& out) {
  const TriangleMesh& mesh = scene.geometry->meshes()[k];
  const Projection proj{scene.camera.calibration()};
  Outline o = outlineOf(Outline::Kind::MeshSilhouette, k, scene.camera.position());
  o.camera = camera;
  const std::vector<MeshEdge>& edges = outlineEdges(mm, o);
  for (uint32_t e = 0; e < edges.size(); ++e) {
    double x0, y0, x1, y1;
    const MeshEdge& edge = edges[e];
    if (outlineEdge(mesh, edge, o.from) && proj.project(Vec3d(mesh.position(edge.v0)), x0, y0) &&
        proj.project(Vec3d(mesh.position(edge.v1)), x1, y1))
      o.edges.add(e, std::hypot(x1 - x0, y1 - y0));
  }
  if (o.edges.total() > 0) out.push_back(std::move(o));
  for (const Vec3d& p : lights) {
    Outline s = outlineOf(Outline::Kind::MeshShadow, k, p);
    s.camera = camera;
    for (uint32_t e = 0; e < edges.size(); ++e)
      if (const MeshEdge& edge = edges[e]; silhouetteEdge(mesh, edge, p))
        s.edges.add(e, length(Vec3d(mesh.position(edge.v1) - mesh.position(edge.v0))));
    if (s.edges.total() > 0) out.push_back(std::move(s));
  }
}

// Every outline a slot moves: the moving analytic primitives' outlines and the shadows' edges
// under each point and spot light (every primitive's, once a shape moves: a moving receiver
// moves them too); the moving meshes' outlines and shadows' edges; when the camera moves, every
// primitive's outline, every mesh's outline and shadows' edges, and every plane's horizon.
std::vector<Outline> movingOutlines(const IntegratorContext& ctx, const PixelRect& rect) {
  const RenderScene& scene = *ctx.scene;
  const ShapeTangents& shapes = ctx.gradients->tangents->shapes;
  const bool camera = !shapes.camera.empty();
  std::vector<Vec3d> lights;
  for (const SceneLight& l : scene.lights) {
    if (const auto* p = std::get_if<PointLight>(&l)) lights.push_back(Vec3d(p->position));
    if (const auto* p = std::get_if<SpotLight>(&l)) lights.push_back(Vec3d(p->position));
  }
  // (a moving mesh or primitive can receive a primitive's shadow)
  const bool anyShape = shapes.movesMeshes() || shapes.movesPrimitives();
  std::vector<Outline> out;
  const GeometryScene& g = *scene.geometry;
  forEachAnalyticKind([&]<class P>() {
    const ShapeKind kind = kShapeKindOf<P>;
    for (uint32_t k = 0; k < g.primitives<P>().size(); ++k) {
      Outline o = outlineOf(Outline::Kind::Silhouette, k, scene.camera.position());
      o.primitive = kind;
      primitiveOutlines(g, kind, k, o.from, o.curves);
      if ((camera || primitiveMoves(shapes, kind, k)) && o.curves.count > 0) out.push_back(o);
      if (!camera && !anyShape) continue;
      for (const Vec3d& p : lights) {
        Outline s = outlineOf(Outline::Kind::Shadow, k, p);
        s.primitive = kind;
        primitiveOutlines(g, kind, k, p, s.curves);
        if (s.curves.count > 0) out.push_back(s);
      }
    }
  });
  for (uint32_t k = 0; k < shapes.meshes.size(); ++k) {
    if (shapes.meshes[k].moves()) meshOutlines(scene, shapes.meshes[k], k, lights, false, out);
    if (camera) meshOutlines(scene, shapes.meshes[k], k, lights, true, out);
  }
  if (camera)
    for (uint32_t k = 0; k < scene.geometry->planes().size(); ++k) {
      const PlaneShape& plane = scene.geometry->planes()[k];
      const Projection proj{scene.camera.calibration()};
      Vec3d ddx, ddy;
      const Vec3d at0 = proj.direction(0, 0, ddx, ddy); // the direction through film (0, 0)
      const Vec3d n = normalize(plane.normal);
      Outline h = outlineOf(Outline::Kind::Horizon, k, scene.camera.position());
      if (clipLine(dot(n, ddx), dot(n, ddy), dot(n, at0), rect, h)) out.push_back(h);
    }
  return out;
}

} // namespace

void primaryBoundary(const IntegratorContext& ctx, const PrimaryBoundaryRequest& req,
                     const std::function<void(const BoundaryContribution&)>& consume,
                     uint64_t& rays) {
  const std::vector<Outline> outlines = movingOutlines(ctx, req.rect);
  for (uint32_t k = 0; k < outlines.size(); ++k) {
    const Outline& o = outlines[k];
    const double pixels = filmLength(ctx, o);
    if (!(pixels > 0)) continue;
    const int64_t count = std::min<int64_t>(
        kMaxSamplesPerOutline,
        std::max<int64_t>(kChunk, static_cast<int64_t>(std::ceil(pixels)) * req.samplesPerPixel));
    const int64_t rounded = (count + kChunk - 1) / kChunk * kChunk;
    const PixelSequence sequence(req.sampler, k, req.seed ^ kBoundarySalt);
    const int64_t chunks = rounded / kChunk;
    // Batches of chunks in parallel, each batch handed over in order (the memory held is a
    // batch's, whatever the outline's length)
    for (int64_t first = 0; first < chunks; first += kBatch) {
      const int64_t n = std::min(kBatch, chunks - first);
      std::vector<std::vector<BoundaryContribution>> parts(static_cast<size_t>(n));
      std::vector<uint64_t> partRays(static_cast<size_t>(n), 0);
      tbb::parallel_for(int64_t{0}, n, [&](int64_t c) {
        sampleOutline(ctx, req, sequence, o, (first + c) * kChunk, kChunk, rounded,
                      parts[static_cast<size_t>(c)], partRays[static_cast<size_t>(c)]);
      });
      for (size_t c = 0; c < parts.size(); ++c) {
        for (const BoundaryContribution& b : parts[c]) consume(b);
        rays += partRays[c];
      }
    }
  }
}

} // namespace nx
