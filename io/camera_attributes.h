#pragma once
// The camera recorded in an image's attributes, so that a file says how to project a 3D point
// into it (OpenCV's conventions: pixel centres at integer coordinates, x right, y down).

#include <map>
#include <string>

#include "core/camera.h"

namespace nx {

/// String attributes for a camera, numbers comma-separated, row-major, exact (the shortest
/// text that reads back as the same double): nxrender.camera.K (3x3), .R (3x3), .t (3), .distortion
/// (k1, k2, p1, p2, k3), .worldToCamera (4x4, [R t; 0 0 0 1]) and, for a thin lens, .thinLens
/// (aperture radius, focus distance).
std::map<std::string, std::string> cameraAttributes(const PinholeCamera& camera);

} // namespace nx
