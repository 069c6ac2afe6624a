#pragma once
// Triangle meshes from PLY and OBJ files.

#include <string>

#include "core/triangle_mesh.h"

namespace nx {

/// Largest mesh file read (bytes): a 1M-triangle binary PLY with normals and uv is about 50 MB.
inline constexpr std::uintmax_t kMaxMeshFileBytes = 4ull << 30;

/// A mesh file's triangles and the bytes it was read from (for the scene's content digest).
struct MeshFile {
  TriangleMesh mesh;
  std::string bytes;
};

/// Reads a triangle mesh from a PLY (ASCII or binary) or Wavefront OBJ file with Assimp:
/// polygons are triangulated, points and lines dropped, the vertex normals and first uv channel
/// kept when the file has them (for every part, or they are dropped), all parts of the file
/// (OBJ groups and objects) merged with their node transforms applied. Materials in the file
/// are ignored (the scene gives the material) and no other file is opened (an OBJ's mtllib is
/// not read). Meshes whose declared size exceeds the memory budget are refused with figures. Throws
/// nx::Error naming the file and the parser's complaint for unreadable, malformed or empty files,
/// indices out of range and non-finite values.
MeshFile readMeshFile(const std::string& path);

/// The same from the file's bytes; `path` names it in errors and its extension (.ply, .obj)
/// says which format the bytes are.
MeshFile meshFromBytes(std::string bytes, const std::string& path);

} // namespace nx
