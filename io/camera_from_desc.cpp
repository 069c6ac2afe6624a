#include "io/camera_from_desc.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/math_util.h"
#include "core/text_table.h"
#include "io/camera_checks.h"

namespace nx {
namespace {

// The rotation nearest to a printed one (polar decomposition by Newton's iteration
// R <- (R + R^-T) / 2), so that rays are exactly what the calibration means.
Matrix3 exactRotation(Matrix3 r) {
  for (int it = 0; it < 20; ++it) {
    const Matrix3 inv = inverse(r);
    Matrix3 next{};
    double change = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        next[i][j] = 0.5 * (r[i][j] + inv[j][i]);
        change = std::max(change, std::abs(next[i][j] - r[i][j]));
      }
    r = next;
    if (change < 1e-16) break;
  }
  return r;
}

// The distortion must map the image one to one: on a 65 x 65 grid over the film (edges
// included) the inverse must converge and the Jacobian of the distortion stay positive
// there (a fold makes two directions meet in one pixel, and no inverse is the right one).
void checkNoFold(const CameraCalibration& cal, int width, int height, const SourceLocation& loc) {
  const int n = 64;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double px = width * static_cast<double>(i) / n - 0.5,
                   py = height * static_cast<double>(j) / n - 0.5;
      const double xd = (px - cal.cx) / cal.fx, yd = (py - cal.cy) / cal.fy;
      double x = 0, y = 0, jac[4], dx = 0, dy = 0;
      const bool ok = cal.undistort(xd, yd, x, y);
      if (ok) cal.distort(x, y, dx, dy, jac);
      if (!ok || !(jac[0] * jac[3] - jac[1] * jac[2] > 0))
        throw Error(loc.str() +
                    ": expected a <distortion> that maps the image one to one, found a fold "
                    "near pixel " +
                    numberText(px) + "," + numberText(py) +
                    " (the coefficients do not describe a lens over this field of view)");
    }
}

PinholeCamera pinhole(const CameraDesc& c, int width, int height) {
  checkCameraDesc(c, width, height); // also what Python edits made of it
  if (!c.intrinsics && !c.extrinsics && c.distortion == std::array<double, 5>{})
    return PinholeCamera(c.position, c.lookAt, c.up, c.fovDegrees, width, height);
  CameraCalibration cal =
      c.extrinsics
          ? CameraCalibration{}
          : PinholeCamera(c.position, c.lookAt, c.up, c.fovDegrees, width, height).calibration();
  if (c.intrinsics) {
    cal.fx = (*c.intrinsics)[0], cal.fy = (*c.intrinsics)[1];
    cal.cx = (*c.intrinsics)[2], cal.cy = (*c.intrinsics)[3];
  } else if (c.extrinsics) {
    cal.fx = cal.fy = 0.5 * width / std::tan(0.5 * c.fovDegrees * kPi / 180.0);
    cal.cx = 0.5 * width - 0.5, cal.cy = 0.5 * height - 0.5;
  }
  if (c.extrinsics) {
    const auto& e = *c.extrinsics;
    cal.R = exactRotation({{{e[0], e[1], e[2]}, {e[3], e[4], e[5]}, {e[6], e[7], e[8]}}});
    cal.t = Vec3d(e[9], e[10], e[11]);
  }
  cal.distortion = c.distortion;
  if (cal.distorted()) checkNoFold(cal, width, height, c.distortionLoc);
  return PinholeCamera(cal, width, height);
}

} // namespace

PinholeCamera cameraFromDesc(const CameraDesc& c, int width, int height) {
  PinholeCamera cam = pinhole(c, width, height);
  if (c.thinLens) cam.setThinLens((*c.thinLens)[0], (*c.thinLens)[1]);
  return cam;
}

} // namespace nx
