#include "core/camera.h"

#include <cmath>

#include "core/error.h"
#include "core/math_util.h"

namespace nx {

PinholeCamera::PinholeCamera(const Vec3d& position, const Vec3d& lookAt, const Vec3d& up,
                             double hfovDegrees, int width, int height)
    : position_(position), width_(width), height_(height) {
  const Vec3d view = lookAt - position;
  if (!(length(view) > 0)) throw Error("camera: position and look_at must differ");
  if (!(hfovDegrees > 0 && hfovDegrees < 180))
    throw Error("camera: field of view must lie in (0, 180) degrees");
  if (width <= 0 || height <= 0) throw Error("camera: image size must be positive");
  forward_ = normalize(view);
  Vec3d preferred = length(up) > 0 ? normalize(up) : Vec3d(0, 1, 0);
  if (std::abs(dot(preferred, forward_)) > 0.999999) {
    // Looking along the up direction: take the world axis least aligned with the view.
    const double ax = std::abs(forward_.x), ay = std::abs(forward_.y), az = std::abs(forward_.z);
    preferred =
        (az <= ax && az <= ay) ? Vec3d(0, 0, 1) : (ax <= ay ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0));
  }
  // Left-handed image frame: right = up x forward, so that +y up and +z forward give +x right.
  right_ = normalize(cross(preferred, forward_));
  up_ = cross(forward_, right_);
  tanHalfX_ = std::tan(0.5 * hfovDegrees * kPi / 180.0);
  tanHalfY_ = tanHalfX_ * height / width;
}

Ray PinholeCamera::generateRay(double x, double y) const {
  const double sx = (2.0 * x / width_ - 1.0) * tanHalfX_;
  const double sy = (1.0 - 2.0 * y / height_) * tanHalfY_;
  const Vec3d d = normalize(forward_ + right_ * sx + up_ * sy);
  Ray r;
  r.o = Vec3(position_);
  r.d = Vec3(d);
  return r;
}

} // namespace nx
