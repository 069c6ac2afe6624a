#pragma once
// A large triangle mesh for the benchmarks: a binary PLY heightfield and a scene that shows it.

#include <string>

namespace nx::bench {

/// Writes a (n+1) x (n+1) vertex grid over [-1, 1]^2 with heights 0.1 sin(8x) cos(8z) as a
/// binary PLY of 2 n^2 triangles.
void writeHeightfieldPly(const std::string& path, int n);

/// Grid size n whose heightfield has about `triangles` triangles.
int heightfieldGridFor(long long triangles);

/// A scene file text showing the PLY `plyFile` (a path relative to the scene) as a matte grey
/// surface lit by a point light, at the given resolution and samples per pixel, seen from
/// `camera` (a scene-file position, "x,y,z") towards the origin.
std::string heightfieldSceneXml(const std::string& plyFile, int width, int height, int spp,
                                const std::string& camera = "0,1.5,-2.5");

} // namespace nx::bench
