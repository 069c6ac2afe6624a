#pragma once
// How the slots of a differentiated render move the scene's geometry (docs/inverse.md, "Shape
// and camera"): per shape, the velocity of its defining numbers per slot. A path vertex on a
// moving shape moves with it (the interior term, geometry_gradients.h); where a moving shape's
// outline separates what a pixel sees, the boundary term is sampled on it
// (primary_boundary.h).

#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace nx {

/// d centre / d slot and d radius / d slot of one sphere.
struct SphereMotion {
  uint32_t slot = 0;
  Vec3d dCenter;
  double dRadius = 0;
};

/// Every slot's motion of the geometry, indexed like the geometry's shapes.
struct ShapeTangents {
  std::vector<std::vector<SphereMotion>> spheres; ///< per GeometryScene::spheres()

  /// True when no slot moves any shape.
  bool empty() const {
    for (const auto& s : spheres)
      if (!s.empty()) return false;
    return true;
  }
};

} // namespace nx
