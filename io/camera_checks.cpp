#include "io/camera_checks.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/math_util.h"
#include "core/params/scene_limits.h"

namespace nx {
namespace {

std::string vectorText(const Vec3d& v) {
  return numberText(v.x) + ", " + numberText(v.y) + ", " + numberText(v.z);
}

// The focal length in pixels that spans `pixels` with the widest field of view allowed.
double shortestFocal(int pixels) {
  return 0.5 * pixels / std::tan(0.5 * kFovRange.hi * kPi / 180);
}

} // namespace

std::string extrinsicsProblem(const std::array<double, 12>& v) {
  double worst = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double dotij = 0;
      for (int k = 0; k < 3; ++k) dotij += v[3 * k + i] * v[3 * k + j];
      worst = std::max(worst, std::abs(dotij - (i == j ? 1.0 : 0.0)));
    }
  const double det = v[0] * (v[4] * v[8] - v[5] * v[7]) - v[1] * (v[3] * v[8] - v[5] * v[6]) +
                     v[2] * (v[3] * v[7] - v[4] * v[6]);
  if (!(worst <= 1e-4) || !(det > 0))
    return "a rotation R in <extrinsics> (R^T R = I within 1e-4, determinant +1), found R^T R "
           "off by " +
           numberText(worst) + ", determinant " + numberText(det);
  if (!(std::abs(v[9]) <= kMaxSceneCoordinate && std::abs(v[10]) <= kMaxSceneCoordinate &&
        std::abs(v[11]) <= kMaxSceneCoordinate))
    return "a translation within 1e12 in <extrinsics>, found " + numberText(v[9]) + ", " +
           numberText(v[10]) + ", " + numberText(v[11]);
  return "";
}

void checkCameraDesc(const CameraDesc& c, int width, int height) {
  const std::string at = c.loc.str() + ": expected ";
  if (c.extrinsics)
    if (const std::string p = extrinsicsProblem(*c.extrinsics); !p.empty()) throw Error(at + p);
  if (!c.extrinsics) {
    const Vec3d view = c.lookAt - c.position;
    if (!(length(view) > 0))
      throw Error(at + "a look_at point different from the camera position, found both at " +
                  vectorText(c.position));
    const double upLength = length(c.up);
    if (!(upLength > 0) || !std::isfinite(upLength))
      throw Error(at + "a non-zero up direction, found " + vectorText(c.up));
    // sin of the angle between up and the view direction: 0 leaves the image's x axis undefined
    if (!(length(cross(view, c.up)) > 1e-9 * length(view) * upLength))
      throw Error(at + "an up direction not parallel to the view direction (look_at - position " +
                  "= " + vectorText(view) + "), found " + vectorText(c.up));
  }
  if (!c.intrinsics && !kFovRange.contains(c.fovDegrees))
    throw Error(at + kFovRange.what + " in (" + numberText(kFovRange.lo) + ", " +
                numberText(kFovRange.hi) + "], found " + numberText(c.fovDegrees));
  if (c.intrinsics) {
    const auto& k = *c.intrinsics;
    if (!(k[0] > 0 && k[1] > 0 && k[0] <= 1e9 && k[1] <= 1e9 && std::abs(k[2]) <= 1e7 &&
          std::abs(k[3]) <= 1e7))
      throw Error(at + "focal lengths fx, fy in (0, 1e9] and a principal point cx, cy within " +
                  "1e7 pixels in <intrinsics>, found " + numberText(k[0]) + ", " +
                  numberText(k[1]) + ", " + numberText(k[2]) + ", " + numberText(k[3]));
    const double fovX = 2 * std::atan(0.5 * width / k[0]) * 180 / kPi,
                 fovY = 2 * std::atan(0.5 * height / k[1]) * 180 / kPi;
    if (!(fovX <= kFovRange.hi && fovY <= kFovRange.hi))
      throw Error(at + "focal lengths fx, fy giving fields of view of at most " +
                  numberText(kFovRange.hi) + " degrees across the " + std::to_string(width) +
                  " x " + std::to_string(height) +
                  " image (fx >= " + numberText(shortestFocal(width)) +
                  ", fy >= " + numberText(shortestFocal(height)) + " pixels), found fx " +
                  numberText(k[0]) + ", fy " + numberText(k[1]));
  }
  for (size_t i = 0; i < c.distortion.size(); ++i)
    if (!(std::abs(c.distortion[i]) <= kMaxDistortionCoefficient))
      throw Error(c.distortionLoc.str() + ": expected distortion coefficients within [-" +
                  numberText(kMaxDistortionCoefficient) + ", " +
                  numberText(kMaxDistortionCoefficient) + "], found " +
                  numberText(c.distortion[i]) + " as coefficient " + std::to_string(i + 1));
  if (c.thinLens) {
    const auto& l = *c.thinLens;
    if (!(l[0] >= 0 && l[0] <= kMaxSceneCoordinate && l[1] > 0 && l[1] <= kMaxSceneCoordinate))
      throw Error(at + "an aperture radius >= 0 and a focus distance > 0 (scene units) in " +
                  "<thin_lens>, found " + numberText(l[0]) + ", " + numberText(l[1]));
  }
}

} // namespace nx
