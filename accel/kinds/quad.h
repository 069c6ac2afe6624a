#pragma once
// A parallelogram, <quad><origin/><edge_u/><edge_v/>: two triangles of a mesh of its own, with
// uv (0, 0) at the origin and (1, 1) at the opposite corner (textures map onto it whole); as an
// emitter the light sampler samples it by solid angle (a rectangle whole, by its spherical
// rectangle).

#include <optional>

#include "accel/shape_schema.h"
#include "core/triangle_mesh.h"

namespace nx {

/// The quad kind.
struct QuadShapeKind {
  static constexpr const char* kName = "quad";
  static constexpr const char* kDoc =
      "a parallelogram origin + s edge_u + t edge_v, s, t in [0, 1] (front face seen from "
      "edge_u x edge_v; uv = (s, t))";
  static constexpr bool kHoldsMedium = false;
  /// Its parameters.
  static std::span<const ShapeParameter> parameters() {
    static const ShapeParameter p[] = {
        {differentiable({"origin", ParamType::Point, "scene units", nullptr,
                         "its corner at uv (0, 0)", "-1, 0, -1", "", "a corner x, y, z"})},
        {differentiable({"edge_u", ParamType::Point, "scene units", nullptr, "its edge along u",
                         "2, 0, 0", "", "an edge vector x, y, z"})},
        {differentiable({"edge_v", ParamType::Point, "scene units", nullptr, "its edge along v",
                         "0, 0, 2", "", "an edge vector x, y, z"})},
    };
    return p;
  }
  /// Parallel or zero edges make no quad.
  static std::optional<ShapeProblem> problem(const ParameterSet& p) {
    if (length(cross(*p.get<Vec3d>("edge_u"), *p.get<Vec3d>("edge_v"))) > 0) return std::nullopt;
    return ShapeProblem{"a quad with non-zero area (edge_u and edge_v not parallel)",
                        "parallel or zero edges"};
  }
  /// Its mesh: two triangles, from checked parameters.
  static TriangleMesh build(const ParameterSet& p, const ShapeInputs&) {
    const Vec3d origin = *p.get<Vec3d>("origin"), edgeU = *p.get<Vec3d>("edge_u"),
                edgeV = *p.get<Vec3d>("edge_v");
    TriangleMesh m;
    const uint32_t a = m.addVertex(Vec3(origin)), b = m.addVertex(Vec3(origin + edgeU)),
                   c = m.addVertex(Vec3(origin + edgeU + edgeV)),
                   d = m.addVertex(Vec3(origin + edgeV));
    m.addTriangle(a, b, c);
    m.addTriangle(a, c, d);
    m.setAttributes({}, {0, 0, 1, 0, 1, 1, 0, 1});
    return m;
  }
};

} // namespace nx
