#pragma once
// The meshes last read from files, by their bytes' size and SHA-256 digest: a program that
// renders many scenes sharing a mesh file (a dataset loop in Python, a parameter sweep) parses
// each file once. The cache keeps one parsed copy of each mesh, shared with its users, and no
// copy of the file's bytes. Read-only to its users; safe from several threads.

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "core/triangle_mesh.h"

namespace nx {

/// Most bytes the cached meshes take (or a quarter of the memory budget, if less); the least
/// recently used are dropped beyond it.
inline constexpr double kMeshCacheBytes = 1024.0 * 1024 * 1024;

/// What a mesh file is cached by: its format, its size and its bytes' SHA-256 digest.
struct MeshKey {
  std::string extension; ///< "ply" or "obj"
  size_t size = 0;
  std::array<uint8_t, 32> digest{};
  bool operator==(const MeshKey&) const = default;
};

/// The key of a file's bytes read as format `extension`.
MeshKey meshKeyOf(const std::string& bytes, const std::string& extension);

/// The mesh parsed from the file of this key, or null.
std::shared_ptr<const TriangleMesh> cachedMesh(const MeshKey& key);

/// Keeps `mesh` as the one parsed from the file of `key`, dropping the least recently used
/// entries beyond the cache's size.
void cacheMesh(const MeshKey& key, std::shared_ptr<const TriangleMesh> mesh);

/// Drops every cached mesh (nxrender.clear_caches()).
void clearMeshCache();

/// Number of meshes cached (tests).
size_t cachedMeshCount();

} // namespace nx
