#pragma once
// How the slots of a differentiated render move the scene's geometry (docs/inverse.md, "Shape
// and camera"): per shape, the velocity of its defining numbers per slot. A path vertex on a
// moving shape moves with it (the interior term, geometry_gradients.h); where a moving shape's
// outline separates what a pixel sees, the boundary term is sampled on it
// (primary_boundary.h).

#include <cstdint>
#include <tuple>
#include <vector>

#include "accel/shape_kinds.h"
#include "core/camera.h"
#include "core/vec3.h"

namespace nx {

/// How one slot moves an analytic primitive of type P: the primitive with the slot's number
/// moved by +-step, as its kind builds it (so every parameter a kind declares differentiable is
/// covered by the code that makes the primitive), differenced in double at a material point
/// carried by the primitive (AnalyticPrimitive::carry).
template <class P>
struct PrimitiveMotion {
  uint32_t slot = 0;
  P plus, minus;
  double step = 1;
  /// The velocity v of the material point at x (on `part`) of `base`, and the turning dn of
  /// its unit normal there, per unit of the slot.
  void at(const P& base, const Vec3d& x, uint32_t part, Vec3d& v, Vec3d& dn) const {
    const CarriedPoint a = base.carry(plus, x, part), b = base.carry(minus, x, part);
    v = (a.p - b.p) * (0.5 / step);
    dn = (a.n - b.n) * (0.5 / step);
  }
};

namespace detail {
template <class Types>
struct MotionsOf;
template <class... P>
struct MotionsOf<PrimitiveTypes<P...>> {
  using type = std::tuple<std::vector<std::vector<PrimitiveMotion<P>>>...>;
};
} // namespace detail

/// Per analytic primitive type, per primitive of the geometry, the slots moving it.
using AnalyticMotions = detail::MotionsOf<AnalyticPrimitives>::type;

/// An edge of a mesh: its two vertices and the one or two triangles that share it (face1 -1
/// for a border edge).
struct MeshEdge {
  uint32_t v0 = 0, v1 = 0;
  int64_t face0 = -1, face1 = -1;
};

/// One slot's velocity of one vertex, listed per vertex (a quad's or a triangle's corners).
struct VertexVelocity {
  uint32_t slot = 0;
  Vec3d velocity;
};

/// How slots move a mesh's vertices. Its vertices as given (rows): vertex v's coordinate k
/// (before the mesh's transform) is slot firstSlot + 3 v + k, its velocity in the scene column
/// k of `linear`. Its transform p -> m p + t (rows of [m | t]): entry (r, c) is slot
/// transformSlot + 4 r + c, moving vertex v by e_r times its coordinate c before the transform
/// (1 for the translation's column). A quad's or a triangle's corners: listed per vertex.
struct MeshMotion {
  int64_t firstSlot = -1;     ///< -1: the vertices are not differentiated
  Vec3d linear[3];            ///< the transform's columns
  int64_t transformSlot = -1; ///< -1: the transform is not differentiated
  std::vector<Vec3d> local;   ///< the vertices before the transform (with transformSlot)
  Vec3d inverseRows[3];       ///< rows of m^-1 (how the transform turns the vertex normals)
  /// Per vertex, the slots moving it besides those above (empty, or one list per vertex)
  std::vector<std::vector<VertexVelocity>> listed;
  std::vector<MeshEdge> edges; ///< every edge that can move, for the outlines
  /// Every edge, welded (coincident vertices one): the outlines that move on the film as the
  /// camera moves (empty unless the camera is differentiated)
  std::vector<MeshEdge> cameraEdges;
  /// True when some slot moves the mesh.
  bool moves() const { return firstSlot >= 0 || transformSlot >= 0 || !listed.empty(); }
  /// The slot moving vertex v's coordinate k.
  uint32_t slot(uint32_t v, int k) const {
    return static_cast<uint32_t>(firstSlot + 3 * static_cast<int64_t>(v) + k);
  }
  /// Calls f(slot, d position / d slot) for every slot moving vertex v.
  template <class F>
  void forEachVelocity(uint32_t v, F&& f) const {
    if (!listed.empty())
      for (const VertexVelocity& l : listed[v]) f(l.slot, l.velocity);
    if (firstSlot >= 0)
      for (int k = 0; k < 3; ++k) f(slot(v, k), linear[k]);
    if (transformSlot < 0) return;
    const Vec3d& x = local[v];
    const double w[4] = {x.x, x.y, x.z, 1.0};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        if (w[c] != 0)
          f(static_cast<uint32_t>(transformSlot + 4 * r + c),
            Vec3d(r == 0 ? w[c] : 0, r == 1 ? w[c] : 0, r == 2 ? w[c] : 0));
  }
  /// Calls f(slot, r, c) for every transform entry that turns normals (m's, not t's).
  template <class F>
  void forEachTurningEntry(F&& f) const {
    if (transformSlot < 0) return;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) f(static_cast<uint32_t>(transformSlot + 4 * r + c), r, c);
  }
};

/// How one slot moves the camera: the camera with the slot's number moved by +-step (a central
/// difference of the camera's own model, so its every parameter is covered by the code that
/// makes its rays).
struct CameraMotion {
  uint32_t slot = 0;
  PinholeCamera plus, minus;
  double step = 1;
  /// d origin / d slot and d direction / d slot of the ray through film position (x, y).
  void ray(double x, double y, Vec3d& dOrigin, Vec3d& dDirection) const {
    Vec3d o0, d0, o1, d1;
    plus.generateRay(x, y, 0, 0, o0, d0);
    minus.generateRay(x, y, 0, 0, o1, d1);
    dOrigin = (o0 - o1) * (0.5 / step);
    dDirection = (d0 - d1) * (0.5 / step);
  }
};

/// Every slot's motion of the geometry, indexed like the geometry's shapes, and of the camera.
struct ShapeTangents {
  AnalyticMotions primitives;     ///< per GeometryScene::primitives<P>()
  std::vector<MeshMotion> meshes; ///< per GeometryScene::meshes()
  std::vector<CameraMotion> camera;

  /// The slots moving each primitive of type P.
  template <class P>
  std::vector<std::vector<PrimitiveMotion<P>>>& motions() {
    return std::get<std::vector<std::vector<PrimitiveMotion<P>>>>(primitives);
  }
  /// The slots moving each primitive of type P.
  template <class P>
  const std::vector<std::vector<PrimitiveMotion<P>>>& motions() const {
    return std::get<std::vector<std::vector<PrimitiveMotion<P>>>>(primitives);
  }
  /// True when some slot moves an analytic primitive.
  bool movesPrimitives() const {
    bool moves = false;
    forEachAnalyticKind([&]<class P>() {
      for (const auto& m : motions<P>()) moves = moves || !m.empty();
    });
    return moves;
  }
  /// True when no slot moves any shape or the camera.
  bool empty() const { return !movesPrimitives() && !movesMeshes() && camera.empty(); }
  /// True when some slot moves a mesh.
  bool movesMeshes() const {
    for (const MeshMotion& m : meshes)
      if (m.moves()) return true;
    return false;
  }
};

} // namespace nx
