#pragma once
// Orthonormal frames built from a single unit vector.

#include "core/vec3.h"

namespace nx {

/// An orthonormal basis (s, t, n); n is the axis the frame was built around.
struct Frame {
  Vec3 s, t, n;

  /// Builds a right-handed frame around unit vector n without branches on a tolerance
  /// (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017).
  static Frame fromNormal(const Vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x),
            Vec3(b, sign + n.y * n.y * a, -n.y), n};
  }

  /// World-space vector v expressed in this frame's coordinates.
  Vec3 toLocal(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  /// Frame-local vector v expressed in world coordinates.
  Vec3 toWorld(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

} // namespace nx
