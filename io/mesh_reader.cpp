#include "io/mesh_reader.h"

#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <vector>

#include "core/error.h"
#include "core/file_text.h"
#include "core/memory.h"
#include "io/mesh_cache.h"
#include "io/mesh_file_check.h"

namespace nx {
namespace {

std::string lowerExtension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

// Appends the triangles of every mesh below `node`, with the accumulated node transform.
void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
             std::vector<std::pair<const aiMesh*, aiMatrix4x4>>& out) {
  const aiMatrix4x4 m = parent * node.mTransformation;
  for (unsigned i = 0; i < node.mNumMeshes; ++i)
    out.emplace_back(scene.mMeshes[node.mMeshes[i]], m);
  for (unsigned i = 0; i < node.mNumChildren; ++i) collect(scene, *node.mChildren[i], m, out);
}

// The file system the mesh library sees besides the mesh itself (given from memory): none. An
// OBJ's mtllib names materials nxrender does not use (a scene assigns materials), so no other
// file is ever opened: no FIFO, directory or huge file can reach the library by that route.
class NoOtherFiles : public Assimp::IOSystem {
public:
  bool Exists(const char*) const override { return false; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char*, const char*) override { return nullptr; }
  void Close(Assimp::IOStream*) override {}
};

MeshFile meshFromBytesUnguarded(std::string bytes, const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext != "ply" && ext != "obj")
    throw Error("expected a mesh file ending in .ply or .obj, found '" + path + "'");
  MeshFile out;
  out.bytes = std::move(bytes);
  const MeshFileCounts counts =
      ext == "ply" ? checkPlyFile(out.bytes, path) : checkObjFile(out.bytes, path);
  // What the mesh library and the mesh need at their peak, from the declared counts (measured
  // with a 1M-face PLY: see kMeshBytesPerFace), checked before the library allocates any of it.
  requireMemory(static_cast<double>(counts.faces) * kMeshBytesPerFace +
                    static_cast<double>(counts.vertices) * kMeshBytesPerVertex +
                    static_cast<double>(out.bytes.size()),
                path, "a mesh",
                std::to_string(counts.vertices) + " vertices and " + std::to_string(counts.faces) +
                    " faces");
  Assimp::Importer importer;
  importer.SetIOHandler(new NoOtherFiles); // owned by the importer
  // Points and lines are dropped, not turned into degenerate triangles.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_SortByPType | aiProcess_ValidateDataStructure;
  const aiScene* scene =
      importer.ReadFileFromMemory(out.bytes.data(), out.bytes.size(), flags, ext.c_str());
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw Error("cannot read mesh '" + path + "': " +
                (importer.GetErrorString()[0] ? importer.GetErrorString()
                                              : "the file holds no complete mesh"));
  std::vector<std::pair<const aiMesh*, aiMatrix4x4>> parts;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), parts);
  size_t vertices = 0, triangles = 0;
  bool normals = true, uv = true;
  for (const auto& [m, x] : parts) {
    vertices += m->mNumVertices;
    triangles += m->mNumFaces;
    normals = normals && m->HasNormals();
    uv = uv && m->HasTextureCoords(0);
  }
  if (triangles == 0) throw Error("cannot read mesh '" + path + "': it holds no triangles");
  if (vertices > 0xffffffffull)
    throw Error("cannot read mesh '" + path + "': more than 2^32 vertices");
  out.mesh.reserve(vertices, triangles);
  std::vector<float> n, t;
  if (normals) n.reserve(3 * vertices);
  if (uv) t.reserve(2 * vertices);
  for (const auto& [m, x] : parts) {
    const uint32_t base = static_cast<uint32_t>(out.mesh.vertexCount());
    aiMatrix3x3 normalMatrix(x);
    normalMatrix.Inverse().Transpose();
    for (unsigned i = 0; i < m->mNumVertices; ++i) {
      const aiVector3D p = x * m->mVertices[i];
      out.mesh.addVertex(Vec3(p.x, p.y, p.z));
      if (normals) {
        const aiVector3D q = normalMatrix * m->mNormals[i];
        n.insert(n.end(), {q.x, q.y, q.z});
      }
      if (uv) t.insert(t.end(), {m->mTextureCoords[0][i].x, m->mTextureCoords[0][i].y});
    }
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices != 3) continue; // sorted out above; never a polygon after triangulation
      out.mesh.addTriangle(base + face.mIndices[0], base + face.mIndices[1],
                           base + face.mIndices[2]);
    }
  }
  out.mesh.setAttributes(std::move(n), std::move(t));
  if (const std::string problem = out.mesh.validate(); !problem.empty())
    throw Error("cannot use mesh '" + path + "': " + problem);
  return out;
}

} // namespace

MeshFile meshFromBytes(std::string bytes, const std::string& path) {
  try {
    return meshFromBytesUnguarded(std::move(bytes), path);
  } catch (const std::bad_alloc&) {
    throw Error(path + ": cannot read the mesh: out of memory (" +
                std::to_string(static_cast<long long>(memoryBudget().bytes / (1 << 20))) +
                " MiB usable: " + memoryBudget().limit + ")");
  }
}

MeshFile readMeshFile(const std::string& path) {
  if (const std::string ext = lowerExtension(path); ext != "ply" && ext != "obj")
    throw Error("expected a mesh file ending in .ply or .obj, found '" + path + "'");
  std::string bytes = readRegularFile(path, kMaxMeshFileBytes, "mesh file");
  // A file read before with the same bytes is not parsed again (io/mesh_cache.h): the caller
  // gets its own copy (it transforms it), the cache keeps the parsed one.
  const MeshKey key = meshKeyOf(bytes, lowerExtension(path));
  if (const auto known = cachedMesh(key)) return {*known, std::move(bytes)};
  MeshFile f = meshFromBytes(std::move(bytes), path);
  cacheMesh(key, std::make_shared<const TriangleMesh>(f.mesh));
  return f;
}

} // namespace nx
