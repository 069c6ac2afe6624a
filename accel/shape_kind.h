#pragma once
// Which kind of shape a hit or a light sample is on (no Embree: light kinds and the scene
// loader use it too).

#include <cstdint>

namespace nx {

/// Which kind of shape a hit is on.
enum class ShapeKind : uint8_t { Sphere, Plane, Triangle, Disk, Cylinder };

} // namespace nx
