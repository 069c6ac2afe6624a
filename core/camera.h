#pragma once
// The pinhole camera of Niixtracer scenes.

#include "core/ray.h"
#include "core/vec3.h"

namespace nx {

/// A pinhole camera. Convention (Niixtracer's, like pbrt's): looking along +z with +y up,
/// +x is on the right of the image. Any look direction works, straight up and down included.
class PinholeCamera {
public:
  /// Camera at `position` looking at `lookAt`; `up` is the preferred up direction (replaced
  /// by the world axis least aligned with the view when parallel to it); horizontal field
  /// of view in degrees (0, 180); image aspect = width / height.
  PinholeCamera(const Vec3d& position, const Vec3d& lookAt, const Vec3d& up, double hfovDegrees,
                int width, int height);

  /// Primary ray through image position (x, y) in pixels: (0, 0) is the top-left corner of
  /// the top-left pixel, x grows to the right and y downwards. Directions are unit length.
  Ray generateRay(double x, double y) const;

  /// Unit right, up and forward vectors of the image plane.
  const Vec3d& right() const { return right_; }
  const Vec3d& up() const { return up_; }
  const Vec3d& forward() const { return forward_; }

private:
  Vec3d position_, right_, up_, forward_;
  double tanHalfX_, tanHalfY_;
  int width_, height_;
};

} // namespace nx
