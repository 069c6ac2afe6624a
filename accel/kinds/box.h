#pragma once
// A box, <box><center/><size/>[<transform/>]: a closed mesh of 12 triangles (flat faces, so
// exact), wound outward; it can hold a <medium>; as a light the light sampler samples its
// faces as a mesh's. Each face has its own uv square, (0, 0) to (1, 1).

#include <array>
#include <optional>

#include "accel/shape_schema.h"
#include "core/error.h"
#include "core/triangle_mesh.h"

namespace nx {

/// The box kind.
struct BoxShapeKind {
  static constexpr const char* kName = "box";
  static constexpr const char* kDoc =
      "an axis-aligned box of `size` around `center`, then moved by an optional <transform> "
      "(a closed mesh of flat faces); it can hold a <medium>";
  static constexpr bool kHoldsMedium = true;
  /// Its parameters.
  static std::span<const ShapeParameter> parameters() {
    static const ShapeParameter p[] = {
        {{"center", ParamType::Point, "scene units", nullptr, "its centre", "0, 0.5, 0", "",
          "a box centre x, y, z"}},
        {{"size", ParamType::Point, "scene units", nullptr, "its edge lengths along x, y and z",
          "1, 1, 1", "", "edge lengths x, y, z"},
         true,
         false,
         [](const ParamValue& v) -> const char* {
           const Vec3d s = std::get<Vec3d>(v);
           return s.x > 0 && s.y > 0 && s.z > 0 ? nullptr : "positive box edge lengths";
         }},
        {differentiable({"transform", ParamType::Transform, "scene units", nullptr,
                         "applied to its corners after it is placed: <translate>, <rotate> "
                         "(axis, degrees), <scale>, <matrix> steps in the order written",
                         "<rotate>0, 1, 0, 30</rotate>"}),
         false},
    };
    return p;
  }
  /// Nothing beyond each value's checks.
  static std::optional<ShapeProblem> problem(const ParameterSet&) { return std::nullopt; }
  /// Its mesh: four corners and two triangles per face, wound so that (b - a) x (c - a)
  /// points out.
  static TriangleMesh build(const ParameterSet& p, const ShapeInputs&) {
    const Vec3d c = *p.get<Vec3d>("center"), h = *p.get<Vec3d>("size") * 0.5;
    // Each face: its outward axis and sign; corners in counter-clockwise order seen from
    // outside.
    TriangleMesh m;
    m.reserve(24, 12);
    std::vector<float> uv;
    for (int axis = 0; axis < 3; ++axis)
      for (const double sign : {-1.0, 1.0}) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3; // u x v = axis
        std::array<Vec3d, 4> q;
        const double su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
        for (int k = 0; k < 4; ++k) {
          double x[3];
          x[axis] = sign;
          x[u] = sign > 0 ? su[k] : sv[k]; // swapping u and v turns the winding for -axis
          x[v] = sign > 0 ? sv[k] : su[k];
          q[static_cast<size_t>(k)] = c + Vec3d(x[0] * h.x, x[1] * h.y, x[2] * h.z);
        }
        const uint32_t a = m.addVertex(Vec3(q[0])), b = m.addVertex(Vec3(q[1])),
                       d = m.addVertex(Vec3(q[2])), e = m.addVertex(Vec3(q[3]));
        m.addTriangle(a, b, d);
        m.addTriangle(a, d, e);
        uv.insert(uv.end(), {0, 0, 1, 0, 1, 1, 0, 1});
      }
    m.setAttributes({}, std::move(uv));
    if (const AffineDesc* t = p.get<AffineDesc>("transform")) {
      m.transform(t->m, t->t);
      if (const std::string problem = m.validate(); !problem.empty())
        throw Error("box after its <transform>: " + problem);
    }
    return m;
  }
};

} // namespace nx
