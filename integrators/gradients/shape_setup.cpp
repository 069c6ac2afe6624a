#include "integrators/gradients/shape_setup.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <variant>

#include "accel/shape_kinds.h"
#include "core/error.h"
#include "core/matrix3.h"
#include "integrators/materials/bsdf.h"
#include "integrators/render_scene.h"
#include "integrators/scene_params/parameter_numbers.h"
#include "integrators/scene_params/parameter_path.h"

namespace nx {
namespace {

// A shape that emits cannot move yet: its light samples would move with it.
[[noreturn]] void refuseMovingEmitter(const std::string& name) {
  throw Error(name + ": moving an emitter is not differentiated yet (its light samples would "
                     "move with it)");
}

// Why a render differentiated with respect to shape would miss a share of its derivative in
// this scene (what the interior and boundary terms do not cover yet), or "".
std::string uncoveredFeature(const RenderScene& scene) {
  if (scene.hasMedia) return "media or interfaces";
  for (const Material& m : scene.materials) {
    if (m.texture || m.concentration) return "a texture or concentration map (the hit's uv moves)";
    if (m.alphaU != m.alphaV) return "anisotropic roughness (its tangent frame moves)";
  }
  for (const SceneLight& l : scene.lights)
    if (std::holds_alternative<EnvironmentLight>(l)) return "an environment map";
  const CameraCalibration& c = scene.camera.calibration();
  if (c.distorted() || scene.camera.hasLens()) return "lens distortion or a thin lens";
  return "";
}

// The inputs of a kind's build where an analytic primitive is rebuilt: it reads no file.
class NoShapeInputs : public ShapeInputs {
public:
  TriangleMesh meshFile(const std::string& path, const AffineDesc&) const override {
    throw Error("internal error: an analytic primitive asked for the mesh file " + path);
  }
  void warn(const std::string&) const override {}
};

// A parameter of object `object`, an analytic primitive (a sphere's centre, a disk's normal, a
// cylinder's end, ...): one slot per number, the primitive rebuilt by its kind with the number
// moved by a small step each way (PrimitiveMotion); nullopt where `leaf` is no differentiable
// shape parameter of the object's kind (an appearance parameter) or the object is no analytic
// primitive.
std::optional<GradientParameter> primitiveParameter(SceneTangents& tangents, const SceneDesc& desc,
                                                    size_t object, const std::string& name,
                                                    const std::string& leaf,
                                                    const RenderScene& base) {
  const ShapeKindSpec* kind = findShapeKind(desc.objects[object].shape);
  const ShapeParameter* declared = kind ? shapeParameter(*kind, leaf) : nullptr;
  if (!declared || !declared->spec.differentiable) return std::nullopt;
  std::optional<GradientParameter> out;
  forEachAnalyticKind([&]<class P>() {
    const std::vector<ShapeAppearance>& shapes = base.shapes(kShapeKindOf<P>);
    for (size_t k = 0; k < shapes.size() && !out; ++k) {
      if (shapes[k].objectId != object + 1) continue;
      if (const std::string why = uncoveredFeature(base); !why.empty())
        throw Error(name + ": derivatives with respect to shape do not cover a scene with " + why +
                    " yet (docs/inverse.md, \"Shape and camera\")");
      if (shapes[k].emission >= 0) refuseMovingEmitter(name);
      const ParameterNumbers n = parameterNumbers(desc, name);
      GradientParameter p{
          name, tangents.slots(), static_cast<uint32_t>(n.values.size()), n.indexed(), {}};
      for (size_t j = 0; j < n.values.size(); ++j) {
        // (relative, down to 1e-9 for values below 1e-3: a small radius keeps its sign)
        const double step = 1e-6 * std::max(1e-3, std::abs(n.values[j]));
        auto primitiveAt = [&](double v) {
          SceneDesc copy = desc;
          std::vector<double> values = n.values;
          values[j] = v;
          const ParameterSet& moved = copy.objects[object].geometry;
          if (!setParameterNumbers(copy, name, values) || shapeProblem(*kind, moved))
            throw Error(name + ": cannot differentiate at " + numberText(n.values[j]) +
                        ": a step of " + numberText(step) + " either way makes no " + kind->name);
          return std::get<P>(kind->build(moved, NoShapeInputs{}));
        };
        tangents.shapes.motions<P>().at(k).push_back({tangents.slots(),
                                                      primitiveAt(n.values[j] + step),
                                                      primitiveAt(n.values[j] - step), step});
        tangents.slotNames.push_back(p.indexed ? name + "[" + std::to_string(j) + "]" : name);
      }
      out = p;
    }
  });
  return out;
}

// The edges of a mesh with the triangles sharing each. `welded`: vertices at the same position
// are one (a box's faces, or a file's vertices split at normal or uv seams, share corners but
// not indices: counted apart, each such edge would be two border edges and its outline counted
// twice); only where every slot moves coincident vertices alike (the transform), not where
// vertices move one by one.
std::vector<MeshEdge> meshEdges(const TriangleMesh& mesh, bool welded) {
  std::vector<uint32_t> canonical(mesh.vertexCount());
  std::map<std::array<float, 3>, uint32_t> at;
  for (uint32_t v = 0; v < canonical.size(); ++v) {
    const Vec3 p = mesh.position(v);
    canonical[v] = welded ? at.try_emplace({p.x, p.y, p.z}, v).first->second : v;
  }
  std::map<std::pair<uint32_t, uint32_t>, size_t> index;
  std::vector<MeshEdge> edges;
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const uint32_t* v = mesh.triangle(t);
    for (int e = 0; e < 3; ++e) {
      const uint32_t p = canonical[v[e]], q = canonical[v[(e + 1) % 3]];
      const uint32_t a = std::min(p, q), b = std::max(p, q);
      const auto [it, fresh] = index.try_emplace({a, b}, edges.size());
      if (fresh)
        edges.push_back({a, b, static_cast<int64_t>(t), -1});
      else
        edges[it->second].face1 = static_cast<int64_t>(t);
    }
  }
  return edges;
}

// The index among the render's meshes of object `object`'s mesh (a mesh or a box), refused
// where shape derivatives do not apply (what uncoveredFeature names, an emitting mesh).
size_t movingMesh(size_t object, const std::string& name, const RenderScene& base) {
  if (const std::string why = uncoveredFeature(base); !why.empty())
    throw Error(name + ": derivatives with respect to shape do not cover a scene with " + why +
                " yet (docs/inverse.md, \"Shape and camera\")");
  int mesh = -1;
  for (size_t k = 0; k < base.meshes.size(); ++k)
    if (base.meshes[k].perTriangle.empty() && base.meshes[k].whole.objectId == object + 1)
      mesh = static_cast<int>(k);
  if (mesh < 0) throw Error("internal error: " + name + ": its mesh was not built");
  if (base.meshes[static_cast<size_t>(mesh)].whole.emission >= 0) refuseMovingEmitter(name);
  return static_cast<size_t>(mesh);
}

// A mesh's vertices given as rows: one slot per coordinate, (vertices, 3).
GradientParameter meshParameter(SceneTangents& tangents, const SceneDesc& desc, size_t object,
                                const std::string& name, const RenderScene& base) {
  if (desc.objects[object].geometry.has("file"))
    throw Error(name + ": the mesh is read from a file: give its vertices as rows (<vertices> "
                       "and <faces>) to differentiate them, or differentiate its transform");
  const size_t mesh = movingMesh(object, name, base);
  const ParameterNumbers n = parameterNumbers(desc, name);
  MeshMotion& motion = tangents.shapes.meshes.at(mesh);
  motion.firstSlot = tangents.slots();
  const AffineDesc* t = desc.objects[object].geometry.get<AffineDesc>("transform");
  const AffineDesc identity;
  const auto& m = (t ? *t : identity).m;
  for (int k = 0; k < 3; ++k) motion.linear[k] = {m[0][k], m[1][k], m[2][k]};
  // Vertices moved one by one: edges by index (replacing welded ones a transform made).
  motion.edges = meshEdges(base.geometry->meshes()[mesh], false);
  GradientParameter p{name, tangents.slots(), static_cast<uint32_t>(n.values.size()), true,
                      n.shape};
  for (size_t j = 0; j < n.values.size(); ++j)
    tangents.slotNames.push_back(name + "[" + std::to_string(j / 3) + "][" + std::to_string(j % 3) +
                                 "]");
  return p;
}

// An object's transform p -> m p + t (a mesh's, read from a file or given as rows, or a box's):
// one slot per entry of its rows [m | t], (3, 4). The vertices before it are recovered from the
// built mesh, m^-1 (p - t).
GradientParameter transformParameter(SceneTangents& tangents, const SceneDesc& desc, size_t object,
                                     const std::string& name, const RenderScene& base) {
  const ParameterNumbers n = parameterNumbers(desc, name); // refuses a transform not given
  const size_t mesh = movingMesh(object, name, base);
  const AffineDesc& t = *desc.objects[object].geometry.get<AffineDesc>("transform");
  const Matrix3 inv = inverse(t.m);
  MeshMotion& motion = tangents.shapes.meshes.at(mesh);
  const TriangleMesh& built = base.geometry->meshes()[mesh];
  motion.local.resize(built.vertexCount());
  for (size_t v = 0; v < built.vertexCount(); ++v) {
    const Vec3d p = Vec3d(built.position(static_cast<uint32_t>(v))) - t.t;
    motion.local[v] = {inv[0][0] * p.x + inv[0][1] * p.y + inv[0][2] * p.z,
                       inv[1][0] * p.x + inv[1][1] * p.y + inv[1][2] * p.z,
                       inv[2][0] * p.x + inv[2][1] * p.y + inv[2][2] * p.z};
  }
  for (int c = 0; c < 3; ++c) motion.inverseRows[c] = {inv[c][0], inv[c][1], inv[c][2]};
  motion.transformSlot = tangents.slots();
  if (motion.firstSlot < 0) motion.edges = meshEdges(built, true);
  GradientParameter p{name, tangents.slots(), 12, true, n.shape};
  for (int j = 0; j < 12; ++j)
    tangents.slotNames.push_back(name + "[" + std::to_string(j / 4) + "][" + std::to_string(j % 4) +
                                 "]");
  return p;
}

// A quad's `origin`, `edge_u` or `edge_v`, or a triangle's `vA`, `vB` or `vC`: three slots (x,
// y, z) moving the corners it places (a quad's mesh: origin, +edge_u, +edge_u+edge_v, +edge_v;
// the inline triangles' mesh: three vertices per triangle in the objects' order). Only the edges
// of the moving corners are outlines that move.
GradientParameter cornerParameter(SceneTangents& tangents, const SceneDesc& desc, size_t object,
                                  const std::string& name, const std::string& leaf,
                                  const RenderScene& base) {
  if (const std::string why = uncoveredFeature(base); !why.empty())
    throw Error(name + ": derivatives with respect to shape do not cover a scene with " + why +
                " yet (docs/inverse.md, \"Shape and camera\")");
  const bool quad = desc.objects[object].shape == "quad";
  size_t mesh = base.meshes.size();
  std::vector<uint32_t> corners;
  for (size_t k = 0; k < base.meshes.size() && corners.empty(); ++k) {
    const MeshAppearance& m = base.meshes[k];
    if (quad && m.perTriangle.empty() && m.whole.objectId == object + 1) {
      if (m.whole.emission >= 0) refuseMovingEmitter(name);
      mesh = k;
      corners = leaf == "origin"   ? std::vector<uint32_t>{0, 1, 2, 3}
                : leaf == "edge_u" ? std::vector<uint32_t>{1, 2}
                                   : std::vector<uint32_t>{2, 3};
    }
    for (size_t t = 0; !quad && t < m.perTriangle.size(); ++t)
      if (m.perTriangle[t].objectId == object + 1) {
        if (m.perTriangle[t].emission >= 0) refuseMovingEmitter(name);
        mesh = k;
        corners = {static_cast<uint32_t>(3 * t + (leaf == "vA" ? 0 : leaf == "vB" ? 1 : 2))};
      }
  }
  if (corners.empty()) throw Error("internal error: " + name + ": its mesh was not built");
  const TriangleMesh& built = base.geometry->meshes()[mesh];
  MeshMotion& motion = tangents.shapes.meshes.at(mesh);
  if (motion.listed.empty()) motion.listed.resize(built.vertexCount());
  GradientParameter p{name, tangents.slots(), 3, true, {}};
  for (int k = 0; k < 3; ++k) {
    const uint32_t slot = tangents.slots();
    const Vec3d e(k == 0 ? 1 : 0, k == 1 ? 1 : 0, k == 2 ? 1 : 0);
    for (uint32_t v : corners) motion.listed[v].push_back({slot, e});
    tangents.slotNames.push_back(name + "[" + std::to_string(k) + "]");
  }
  // The edges of the corners that move (of a gathered mesh of triangles, not every triangle's).
  motion.edges.clear();
  for (const MeshEdge& e : meshEdges(built, false))
    if (!motion.listed[e.v0].empty() || !motion.listed[e.v1].empty()) motion.edges.push_back(e);
  return p;
}

// The camera's parameter `name`: one slot per number, the camera resolved with it moved by a
// small step each way.
GradientParameter cameraParameter(SceneTangents& tangents, const SceneDesc& desc,
                                  const std::string& name, const RenderScene& base) {
  if (const std::string why = uncoveredFeature(base); !why.empty())
    throw Error(name + ": derivatives with respect to the camera do not cover a scene with " + why +
                " yet (docs/inverse.md, \"Shape and camera\")");
  const GeometryScene& g = *base.geometry;
  // Every mesh's outline moves on the film and as seen from every vertex the camera moves.
  for (size_t k = 0; k < g.meshes().size(); ++k)
    if (tangents.shapes.meshes[k].cameraEdges.empty())
      tangents.shapes.meshes[k].cameraEdges = meshEdges(g.meshes()[k], true);
  const ParameterNumbers n = parameterNumbers(desc, name);
  GradientParameter p{
      name, tangents.slots(), static_cast<uint32_t>(n.values.size()), n.indexed(), {}};
  for (size_t j = 0; j < n.values.size(); ++j) {
    const double step = 1e-4 * std::max(1.0, std::abs(n.values[j]));
    auto cameraAt = [&](double v) {
      SceneDesc copy = desc;
      std::vector<double> values = n.values;
      values[j] = v;
      if (!setParameterNumbers(copy, name, values))
        throw Error(name + ": cannot differentiate at " + std::to_string(n.values[j]) +
                    ": a step of " + std::to_string(step) + " either way is refused");
      return resolveRenderScene(copy).camera;
    };
    tangents.shapes.camera.push_back(
        {tangents.slots(), cameraAt(n.values[j] + step), cameraAt(n.values[j] - step), step});
    tangents.slotNames.push_back(p.indexed ? name + "[" + std::to_string(j) + "]" : name);
  }
  return p;
}

} // namespace

std::optional<GradientParameter> shapeParameter(SceneTangents& tangents, const SceneDesc& desc,
                                                const std::string& name, const RenderScene& base) {
  if (name == "camera.position" || name == "camera.look_at" || name == "camera.fov" ||
      name == "camera.extrinsics")
    return cameraParameter(tangents, desc, name, base);
  const std::vector<ParameterStep> steps = parameterSteps(name);
  if (steps.size() != 2 || steps[0].attribute != "objects" ||
      !std::holds_alternative<size_t>(steps[0].index))
    return std::nullopt;
  const size_t object = std::get<size_t>(steps[0].index);
  if (object >= desc.objects.size()) return std::nullopt;
  const ObjectDesc& o = desc.objects[object];
  const std::string& leaf = steps[1].attribute;
  if (o.shape == "mesh" && leaf == "vertices")
    return meshParameter(tangents, desc, object, name, base);
  if (leaf == "transform") return transformParameter(tangents, desc, object, name, base);
  if ((o.shape == "quad" && (leaf == "origin" || leaf == "edge_u" || leaf == "edge_v")) ||
      (o.shape == "triangle" && (leaf == "vA" || leaf == "vB" || leaf == "vC")))
    return cornerParameter(tangents, desc, object, name, leaf, base);
  return primitiveParameter(tangents, desc, object, name, leaf, base);
}

std::vector<std::string> shapeCoverageWarnings(const RenderScene& scene,
                                               const SceneTangents& tangents) {
  const ShapeTangents& shapes = tangents.shapes;
  std::vector<std::string> out;
  if (shapes.empty()) return out;
  const std::string where = " (docs/inverse.md, \"Shape and camera\", \"Not covered\")";
  // Point and spot lights' shadow edges are sampled on the film only.
  bool deltaLight = false;
  for (const SceneLight& l : scene.lights)
    deltaLight = deltaLight || !std::holds_alternative<EnvironmentLight>(l);
  if (deltaLight && scene.settings.depth >= 2)
    out.push_back("warning: shape derivatives: the edges of point and spot lights' shadows are "
                  "sampled where the camera sees them, not where a surface sees them after a "
                  "bounce: their share of the derivative there is missed" +
                  where);
  // Delta lobes: an outline seen in a mirror or through glass is not sampled.
  for (const Material& m : scene.materials) {
    // Delta lobes, and a rough dielectric's refraction (anisotropic metals are refused).
    const bool delta = (materialLobes(m) &
                        (kSpecularReflection | kSpecularTransmission | kGlossyTransmission)) != 0;
    if (delta) {
      out.push_back("warning: shape derivatives: outlines seen in a mirror reflection or "
                    "through smooth glass or a clear coat are not sampled: their share of the "
                    "derivative is missed" +
                    where);
      break;
    }
  }
  // Outlines of meshes that do not move, seen from a point a shape's slot moves (analytic
  // primitives' are sampled; as the camera moves, every mesh's is).
  if (shapes.movesMeshes() || shapes.movesPrimitives()) {
    bool staticMesh = false;
    for (const MeshMotion& m : shapes.meshes) staticMesh = staticMesh || !m.moves();
    if (staticMesh)
      out.push_back("warning: shape derivatives: the outlines of meshes, quads and triangles "
                    "that do not move, seen from a point on a shape that moves, are not sampled: "
                    "their share of the derivative is missed" +
                    where);
  }
  return out;
}

} // namespace nx
