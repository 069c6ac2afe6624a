#pragma once
// Whether a triangle mesh bounds a volume (so it can hold a medium), which way its triangles
// face, and whether a point lies inside it.

#include <string>

#include "core/triangle_mesh.h"
#include "core/vec3.h"

namespace nx {

/// What a mesh encloses.
struct MeshClosure {
  /// Every edge (vertices matched by position) is shared by exactly two triangles that run
  /// along it in opposite directions: a closed, consistently wound surface.
  bool closed = false;
  /// Signed volume: sum over triangles of dot(a, b x c) / 6; positive when (b - a) x (c - a)
  /// points out of the volume.
  double volume = 0;
  std::string problem; ///< why it is not closed ("an edge used by 1 triangle", ...)
};

/// The closure of mesh m.
MeshClosure meshClosure(const TriangleMesh& m);

/// True when p lies inside the closed mesh m: an odd number of crossings along a fixed
/// direction (chosen off every axis and diagonal, so grazing an edge is unlikely).
bool insideClosedMesh(const TriangleMesh& m, const Vec3d& p);

} // namespace nx
