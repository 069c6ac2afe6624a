#pragma once
// A triangle mesh file, <mesh file="x.ply|x.obj"><transform>...</transform>: read by the mesh
// reader (io/mesh_reader.h: assimp, checked before), moved by its transform, one Embree
// triangle geometry reading its buffers; a closed one can hold a <medium>; as an emitter the
// light sampler samples its triangles by solid angle (more than 4 through its light tree).

#include <optional>

#include "accel/shape_schema.h"
#include "accel/triangle_mesh.h"

namespace nx {

/// The mesh kind.
struct MeshShapeKind {
  static constexpr const char* kName = "mesh";
  static constexpr const char* kDoc =
      "a triangle mesh from a .ply or .obj file, moved by a <transform>; a closed one can hold "
      "a <medium>";
  static constexpr bool kHoldsMedium = true;
  /// Its parameters.
  static std::span<const ShapeParameter> parameters() {
    static const ShapeParameter p[] = {
        {{"file", ParamType::File, "", nullptr,
          "the mesh file (.ply or .obj), relative to the scene file", "bunny.ply", "",
          "a .ply or .obj mesh"},
         true,
         true},
        {{"transform", ParamType::Transform, "scene units", nullptr,
          "applied to its vertices: <translate>, <rotate> (axis, degrees), <scale>, <matrix> "
          "steps in the order written",
          "<translate>0, 1, 0</translate>"},
         false},
    };
    return p;
  }
  /// Nothing beyond each value's type (the file is checked when it is read).
  static std::optional<ShapeProblem> problem(const ParameterSet&) { return std::nullopt; }
  /// Its mesh, read and transformed.
  static TriangleMesh build(const ParameterSet& p, const ShapeInputs& in) {
    const AffineDesc* t = p.get<AffineDesc>("transform");
    return in.meshFile(*p.get<std::string>("file"), t ? *t : AffineDesc{});
  }
};

} // namespace nx
