#pragma once
// A triangle mesh, from a file, <mesh file="x.ply|x.obj">, or from rows of numbers written
// inline (<vertices>, <faces>, optional <normals> and <uv>; Python's arrays), moved by its
// <transform>, one Embree triangle geometry reading its buffers; a closed one can hold a
// <medium>; as an emitter the light sampler samples its triangles by solid angle (more than 4
// through its light tree). Both forms are checked alike (indices in range, finite values,
// triangles of zero area counted and warned about) and give the same mesh for the same numbers.

#include <optional>

#include "accel/shape_schema.h"
#include "core/error.h"
#include "core/memory.h"
#include "core/triangle_mesh.h"

namespace nx {

/// The mesh kind.
struct MeshShapeKind {
  static constexpr const char* kName = "mesh";
  static constexpr const char* kDoc =
      "a triangle mesh from a .ply or .obj file or from rows of vertices and faces, moved by a "
      "<transform>; a closed one can hold a <medium>";
  static constexpr bool kHoldsMedium = true;
  /// Its parameters.
  static std::span<const ShapeParameter> parameters() {
    static const ShapeParameter p[] = {
        {{"file", ParamType::File, "", nullptr,
          "the mesh file (.ply or .obj), relative to the scene file; or give <vertices> and "
          "<faces>",
          "bunny.ply", "vertices faces normals uv", "a .ply or .obj mesh"},
         false,
         true},
        {differentiable({"vertices", ParamType::Reals, "scene units", nullptr,
                         "vertex positions x y z, one row per vertex (instead of a file)",
                         "0 0 0, 1 0 0, 0 1 0", "file", "x, y, z per vertex", 3}),
         false},
        {{"faces", ParamType::Indices, "", nullptr,
          "triangles as three vertex indices (from 0), one row per triangle", "0 1 2", "file",
          "three vertex indices per triangle", 3},
         false},
        {{"normals", ParamType::Reals, "", nullptr,
          "per-vertex shading normals x y z, one row per vertex (optional)", "0 0 1, 0 0 1, 0 0 1",
          "file", "x, y, z per vertex", 3},
         false},
        {{"uv", ParamType::Reals, "", nullptr,
          "per-vertex texture coordinates u v, one row per vertex (optional)", "0 0, 1 0, 0 1",
          "file", "u, v per vertex", 2},
         false},
        {differentiable({"transform", ParamType::Transform, "scene units", nullptr,
                         "applied to its vertices: <translate>, <rotate> (axis, degrees), "
                         "<scale>, <matrix> steps in the order written",
                         "<translate>0, 1, 0</translate>"}),
         false},
    };
    return p;
  }
  /// Either a file or vertices and faces; normals and uv only with vertices, one row each;
  /// faces' indices within the vertices.
  static std::optional<ShapeProblem> problem(const ParameterSet& p) {
    const ArrayDesc* v = p.get<ArrayDesc>("vertices");
    const ArrayDesc* f = p.get<ArrayDesc>("faces");
    if (p.has("file") == (v || f))
      return ShapeProblem{"either file=\"...\" or <vertices> and <faces> on a mesh",
                          p.has("file") ? "both" : "neither"};
    if (p.has("file")) return std::nullopt;
    if (!v || !f)
      return ShapeProblem{"<vertices> and <faces> together on a mesh",
                          v ? "no <faces>" : "no <vertices>"};
    for (const char* name : {"normals", "uv"})
      if (const ArrayDesc* a = p.get<ArrayDesc>(name); a && a->rows() != v->rows())
        return ShapeProblem{"one row of <" + std::string(name) + "> per vertex (" +
                                std::to_string(v->rows()) + ")",
                            std::to_string(a->rows()) + " rows"};
    const std::vector<uint32_t>& idx = *f->indices;
    for (size_t i = 0; i < idx.size(); ++i)
      if (idx[i] >= v->rows())
        return ShapeProblem{
            "face indices below the vertex count (" + std::to_string(v->rows()) + ")",
            "face " + std::to_string(i / 3) + " refers to vertex " + std::to_string(idx[i])};
    return std::nullopt;
  }
  /// Its mesh, read or made from its rows, and transformed.
  static TriangleMesh build(const ParameterSet& p, const ShapeInputs& in) {
    const AffineDesc* t = p.get<AffineDesc>("transform");
    TriangleMesh m = p.has("file") ? in.meshFile(*p.get<std::string>("file"), t ? *t : AffineDesc{})
                                   : meshOfRows(p, t ? *t : AffineDesc{});
    if (const size_t flat = m.zeroAreaTriangles())
      in.warn(std::to_string(flat) + " of the mesh's " + std::to_string(m.triangleCount()) +
              " triangles have zero area (they are never hit)");
    return m;
  }

private:
  // The mesh of checked rows, checked and transformed as a file's is.
  static TriangleMesh meshOfRows(const ParameterSet& p, const AffineDesc& t) {
    const ArrayDesc& v = *p.get<ArrayDesc>("vertices");
    const std::vector<float>& xyz = *v.reals;
    const std::vector<uint32_t>& idx = *p.get<ArrayDesc>("faces")->indices;
    // Checked as a mesh file is, before the mesh and its acceleration structure are built.
    requireMemory(static_cast<double>(idx.size() / 3) * kMeshBytesPerFace +
                      static_cast<double>(v.rows()) * kMeshBytesPerVertex,
                  "mesh of <vertices> and <faces>", "a mesh",
                  std::to_string(v.rows()) + " vertices and " + std::to_string(idx.size() / 3) +
                      " faces");
    TriangleMesh m;
    m.reserve(v.rows(), idx.size() / 3);
    for (size_t i = 0; i < v.rows(); ++i)
      m.addVertex(Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
    for (size_t i = 0; i < idx.size(); i += 3) m.addTriangle(idx[i], idx[i + 1], idx[i + 2]);
    const ArrayDesc* n = p.get<ArrayDesc>("normals");
    const ArrayDesc* uv = p.get<ArrayDesc>("uv");
    m.setAttributes(n ? *n->reals : std::vector<float>{}, uv ? *uv->reals : std::vector<float>{});
    if (const std::string problem = m.validate(); !problem.empty())
      throw Error("mesh of <vertices> and <faces>: " + problem);
    m.transform(t.m, t.t);
    if (const std::string problem = m.validate(); !problem.empty())
      throw Error("mesh of <vertices> and <faces> after its <transform>: " + problem);
    return m;
  }
};

} // namespace nx
