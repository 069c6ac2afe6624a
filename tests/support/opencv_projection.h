#pragma once
// OpenCV's camera model written out for tests, independently of nxrender's ray generation:
// the projection of cv::projectPoints and the rotation of cv::Rodrigues.

#include <cmath>

#include "core/camera.h"

namespace nx::test {

// OpenCV's projection (the formulas of cv::projectPoints, written here independently of the
// camera's ray generation): world point to pixel coordinates, centres at integers.
inline void projectOpenCv(const CameraCalibration& c, const Vec3d& X, double& u, double& v) {
  const Vector3d xc = multiply(c.R, {X.x, X.y, X.z});
  const double x = (xc[0] + c.t.x) / (xc[2] + c.t.z), y = (xc[1] + c.t.y) / (xc[2] + c.t.z);
  const double k1 = c.distortion[0], k2 = c.distortion[1], p1 = c.distortion[2],
               p2 = c.distortion[3], k3 = c.distortion[4];
  const double r2 = x * x + y * y, r4 = r2 * r2, r6 = r4 * r2;
  const double radial = 1 + k1 * r2 + k2 * r4 + k3 * r6;
  const double xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x);
  const double yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
  u = c.fx * xd + c.cx;
  v = c.fy * yd + c.cy;
}

// Rotation from a Rodrigues vector (axis times angle), as cv::Rodrigues.
inline Matrix3 rodrigues(const Vec3d& w) {
  const double a = length(w);
  const Vec3d k = w / a;
  const double c = std::cos(a), s = std::sin(a), C = 1 - c;
  return {{{c + k.x * k.x * C, k.x * k.y * C - k.z * s, k.x * k.z * C + k.y * s},
           {k.y * k.x * C + k.z * s, c + k.y * k.y * C, k.y * k.z * C - k.x * s},
           {k.z * k.x * C - k.y * s, k.z * k.y * C + k.x * s, c + k.z * k.z * C}}};
}

} // namespace nx::test
