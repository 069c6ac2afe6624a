#pragma once
// The meshes last read from files, by their bytes: a program that renders many scenes sharing
// a mesh file (a dataset loop in Python, a parameter sweep) parses each file once. Read-only to
// its users; safe from several threads.

#include <memory>
#include <string>

#include "core/triangle_mesh.h"

namespace nx {

/// Most bytes the cached meshes and their files' bytes take (or a quarter of the memory
/// budget, if less); the least recently used are dropped beyond it.
inline constexpr double kMeshCacheBytes = 1024.0 * 1024 * 1024;

/// The mesh parsed from exactly these bytes as format `extension` ("ply", "obj"), or null.
/// Found by the bytes' length and hash, then compared byte for byte (never a different file's).
std::shared_ptr<const TriangleMesh> cachedMesh(const std::string& bytes,
                                               const std::string& extension);

/// Keeps mesh as the one parsed from bytes (a copy of both), dropping the least recently used
/// entries beyond the cache's size.
void cacheMesh(const std::string& bytes, const std::string& extension, const TriangleMesh& mesh);

/// Number of meshes cached (tests).
size_t cachedMeshCount();

} // namespace nx
