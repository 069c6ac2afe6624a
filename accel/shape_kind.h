#pragma once
// Which kind of shape a hit or a light sample is on (no Embree: light kinds and the scene
// loader use it too), and the one list of analytic primitives everything else is generated
// from (accel/primitive.h says what such a primitive owns).

#include <cstddef>
#include <cstdint>

namespace nx {

/// The analytic primitives: X(Name) for each NameShape of accel/kinds/ (Embree user geometry,
/// exact intersection). Adding one: its header and a line here and in accel/shape_kinds.h.
#define NX_ANALYTIC_PRIMITIVES(X)                                                                  \
  X(Sphere)                                                                                        \
  X(Disk)                                                                                          \
  X(Cylinder)                                                                                      \
  X(Capsule)                                                                                       \
  /* (one line per primitive, each ending in a backslash) */

#define NX_SHAPE_KIND_ENUMERATOR(Name) Name,
/// Which kind of shape a hit is on: a plane (outside the BVH), a triangle of a mesh, or one of
/// the analytic primitives.
enum class ShapeKind : uint8_t {
  Plane,
  Triangle,
  NX_ANALYTIC_PRIMITIVES(NX_SHAPE_KIND_ENUMERATOR)
};
#undef NX_SHAPE_KIND_ENUMERATOR

#define NX_SHAPE_KIND_COUNT(Name) +1
/// How many shape kinds there are.
inline constexpr size_t kShapeKindCount = 2 NX_ANALYTIC_PRIMITIVES(NX_SHAPE_KIND_COUNT);
#undef NX_SHAPE_KIND_COUNT

} // namespace nx
