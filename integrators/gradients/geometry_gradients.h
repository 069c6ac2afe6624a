#pragma once
// The interior term of derivatives with respect to shape (docs/inverse.md, "Shape and camera").
// A path is parameterised as it was sampled: the camera ray by its film position, each
// continuation by its direction (a delta lobe's direction moves with its surface: it is a
// function of the normal and the arriving direction), each light sample by its point on the
// light. As a slot moves a shape, the vertices move along their fixed rays (a ray's origin and
// direction move with the vertex it leaves), their normals turn, and the factors f_i of the
// contribution change through their arguments: g = f' / f enters the tape like any other
// parameter's (path_gradients.h), the sampling densities held. The derivative of each factor
// comes from its kind's own evaluation: the BSDF and its delta lobes are evaluated at normals and
// directions moved a little each way along the slot's motion (central differences of a smooth
// function, Richardson-extrapolated, with steps scaled to the lobe: about 1e-5 relative, far
// below the Monte Carlo noise), so every material kind is
// covered by the code that renders it. Where visibility changes, the boundary term is separate
// (primary_boundary.h).

#include <cmath>
#include <cstdint>
#include <vector>

#include "accel/geometry_scene.h"
#include "core/ray.h"
#include "integrators/gradients/shape_tangents.h"
#include "integrators/materials/bsdf.h"
#include "spectra/sampled_wavelengths.h"

namespace nx {

/// How one slot moves the ray a path follows: its origin and its unit direction.
struct RayMotion {
  uint32_t slot = 0;
  Vec3 dOrigin, dDir;
};

/// How one slot moves a surface vertex: its point, its geometric and shading normals, and the
/// direction the path arrived along.
struct VertexMotion {
  uint32_t slot = 0;
  Vec3 dp, dng, dns, dDir;
};

/// The lobe a continuation took, kept for the emitter its ray may find: its value f at the
/// direction wi and the derivatives d1, d2 of f as wi turns towards e1 and e2 (both
/// perpendicular to wi). Next-event estimation holds a light's point (area measure) where the
/// continuation holds its direction: so that both strategies of multiple importance sampling
/// estimate one parameterisation (their weights are held, and a mixture of two
/// parameterisations' derivatives weighted by anything but 1 is biased), an emitter found by
/// the continuation is differentiated with its point held too (integrators/path_walk.h).
struct ContinuationLobe {
  bool valid = false;
  Vec3 wi, e1, e2;
  SampledSpectrum f, d1, d2;
};

/// The geometric derivative's state along one path (kept in the tape, reused).
struct PathMotion {
  /// The camera ray's motion (the camera's slots), set per sample by the renderer and kept by
  /// GradientTape::clear()
  std::vector<RayMotion> primary;
  ContinuationLobe lobe;      ///< the last continuation's (valid when it was not a delta lobe)
  std::vector<RayMotion> ray; ///< the current ray's motion (empty: it does not move)
  std::vector<VertexMotion> vertex;               ///< the current vertex's motion
  std::vector<std::pair<uint32_t, double>> rates; ///< scratch: an outline's rates per slot
};

/// How one slot moves the surface at a hit: the velocity of its material point there, the
/// turning of its geometric normal (a mesh's face as its vertices move) and the shading
/// normal's own turning (a mesh's vertex normals turned by its transform).
struct SurfaceSlot {
  uint32_t slot;
  Vec3 v, dn, dns;
};

/// The slots moving the surface at `hit` into `out`: an analytic primitive's (its material
/// point's velocity and its normal's turning, PrimitiveMotion) and a moving mesh's three
/// vertices' coordinates (v = b_j u, the face normal turning by (I - n n^T) dN / |N|,
/// N = (B - A) x (C - A)).
void surfaceSlots(const ShapeTangents& shapes, const GeometryScene& geometry, const SurfaceHit& hit,
                  std::vector<SurfaceSlot>& out);

/// How the slots move the vertex `hit` of `ray` (unit direction; its motion `rayMotion`): the
/// ray's own motion carried to the surface, and the surface's where a slot moves it, with the
/// normals' turning (a sphere's and a cylinder's curvature, a mesh's interpolated normals).
void vertexMotion(const ShapeTangents& shapes, const GeometryScene& geometry, const Ray& ray,
                  const std::vector<RayMotion>& rayMotion, const SurfaceHit& hit,
                  std::vector<VertexMotion>& out);

/// The outline of analytic primitive (kind, index) seen from o (AnalyticPrimitive::outlines).
inline void primitiveOutlines(const GeometryScene& geometry, ShapeKind kind, uint32_t index,
                              const Vec3d& o, OutlineCurves& out) {
  out.count = 0;
  geometry.visitPrimitive(kind, index, [&](const auto& shape) { shape.outlines(o, out); });
}

/// True when some slot moves analytic primitive (kind, index).
inline bool primitiveMoves(const ShapeTangents& shapes, ShapeKind kind, uint32_t index) {
  return visitAnalyticKind(kind, [&]<class P>() {
    const auto& motions = shapes.motions<P>();
    return index < motions.size() && !motions[index].empty();
  });
}

/// Calls f(slot, v) for every slot moving analytic primitive (kind, index), v the velocity of
/// its material point at x on `part` (PrimitiveMotion::at).
template <class F>
void forEachPrimitiveVelocity(const ShapeTangents& shapes, const GeometryScene& geometry,
                              ShapeKind kind, uint32_t index, const Vec3d& x, uint32_t part,
                              F&& f) {
  visitAnalyticKind(kind, [&]<class P>() {
    const auto& motions = shapes.motions<P>();
    if (index >= motions.size()) return;
    const P& base = geometry.primitives<P>()[index];
    for (const PrimitiveMotion<P>& m : motions[index]) {
      Vec3d v, dn;
      m.at(base, x, part, v, dn);
      f(m.slot, v);
    }
  });
}

/// The unit normal of the plane through a viewpoint `from` and the tangent dm of an outline
/// at its point m: across the outline as seen from there (the surface's normal at a
/// silhouette); zero where the outline is seen end-on.
inline Vec3d outlineNormal(const Vec3d& from, const Vec3d& m, const Vec3d& dm) {
  const Vec3d n = cross(m - from, dm);
  const double len = length(n);
  return len > 0 && std::isfinite(len) ? n / len : Vec3d();
}

/// Adds `rate` to slot's entry of an outline's rates (d phi / d slot), or appends one.
inline void addRate(std::vector<std::pair<uint32_t, double>>& rates, uint32_t slot, double rate) {
  for (auto& [s, r] : rates)
    if (s == slot) {
      r += rate;
      return;
    }
  rates.push_back({slot, rate});
}

/// d g / d s at s = 0 of a smooth g(s) (a value per lane, or a vector) from its values at
/// +-h and +-h/2: central differences Richardson-extrapolated,
/// (8 (g(h/2) - g(-h/2)) - (g(h) - g(-h))) / (6 h), whose truncation error is O(h^4) where a
/// plain central difference's is O(h^2) (Richardson 1911; the extrapolation of a sequence of
/// differences with steps halved).
template <class T, class At>
T richardsonDerivative(At&& at, float h) {
  const T p1 = at(h), m1 = at(-h), p2 = at(0.5f * h), m2 = at(-0.5f * h);
  return ((p2 + m2 * -1.0f) * 8.0f + (p1 + m1 * -1.0f) * -1.0f) * (1.0f / (6.0f * h));
}

/// d value / d s at s = 0 of value(ng + s dng, ns + s dns, wo + s dwo, wi + s dwi), each
/// argument renormalised: Richardson-extrapolated central differences (richardsonDerivative)
/// with the unit vectors turned by at most the kind's steps (bsdfDerivativeSteps: 1e-3, or an
/// eighth of a narrow lobe's width). Where the normals' step differs from the directions',
/// the two parts are differenced apart and summed (the derivative is linear in the motion).
/// Measured against Ridders' extrapolation over every material kind's examples, down to a
/// roughness of 0.01, the median relative error is below 1e-4 (float evaluations bound it:
/// test_material_conformance.cpp, "Derivatives").
template <class Value>
SampledSpectrum directionalDerivative(Value&& value, const BsdfDerivativeSteps& steps,
                                      const Vec3& ng, const Vec3& ns, const Vec3& wo,
                                      const Vec3& wi, const Vec3& dng, const Vec3& dns,
                                      const Vec3& dwo, const Vec3& dwi) {
  auto part = [&](const Vec3& tg, const Vec3& ts, const Vec3& to, const Vec3& ti, float step) {
    const float scale = std::max({length(tg), length(ts), length(to), length(ti)});
    if (!(scale > 0) || !std::isfinite(scale)) return SampledSpectrum();
    return richardsonDerivative<SampledSpectrum>(
        [&](float s) {
          return value(normalize(ng + tg * s), normalize(ns + ts * s), normalize(wo + to * s),
                       normalize(wi + ti * s));
        },
        step / scale);
  };
  if (steps.normals == steps.directions) return part(dng, dns, dwo, dwi, steps.directions);
  return part(dng, dns, Vec3(), Vec3(), steps.normals) +
         part(Vec3(), Vec3(), dwo, dwi, steps.directions);
}

/// d wi / d s of the unit direction wi = (y - p) / d towards a fixed point y at distance d as
/// p moves by dp.
inline Vec3 towardsFixedPoint(const Vec3& wi, float distance, const Vec3& dp) {
  return (dp - wi * dot(wi, dp)) * (-1.0f / distance);
}

/// Emits (slot, lane, d / v + extra) per lane of the derivative d of a factor of value v (its
/// log-derivative). A lane with v = 0 is skipped: the factors here are continuous in the
/// geometry (a BSDF's value falls to 0 at the horizon with its cosine), so where one is 0 its
/// derivative is 0 too, and a difference straddling the horizon is not one.
template <class Emit>
void logDerivativeEvents(uint32_t slot, const SampledSpectrum& d, const SampledSpectrum& v,
                         float extra, Emit&& emit) {
  for (int i = 0; i < kLanes; ++i) {
    if (!(v[i] != 0)) continue;
    const float g = d[i] / v[i] + extra;
    if (g != 0 && std::isfinite(g)) emit(slot, i, g);
  }
}

} // namespace nx
