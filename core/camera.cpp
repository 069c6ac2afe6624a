#include "core/camera.h"

#include <cmath>

#include "core/error.h"
#include "core/math_util.h"

namespace nx {

bool CameraCalibration::distorted() const {
  for (double k : distortion)
    if (k != 0) return true;
  return false;
}

void CameraCalibration::distort(double x, double y, double& xd, double& yd,
                                double* jacobian) const {
  const double k1 = distortion[0], k2 = distortion[1], p1 = distortion[2], p2 = distortion[3],
               k3 = distortion[4];
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x);
  yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
  if (jacobian) {
    const double dRadial = k1 + r2 * (2 * k2 + 3 * k3 * r2); // d radial / d r2
    jacobian[0] = radial + 2 * x * x * dRadial + 2 * p1 * y + 6 * p2 * x;
    jacobian[1] = 2 * x * y * dRadial + 2 * p1 * x + 2 * p2 * y;
    jacobian[2] = 2 * x * y * dRadial + 2 * p1 * x + 2 * p2 * y;
    jacobian[3] = radial + 2 * y * y * dRadial + 6 * p1 * y + 2 * p2 * x;
  }
}

bool CameraCalibration::undistort(double xd, double yd, double& x, double& y) const {
  x = xd, y = yd;
  for (int i = 0; i < 50; ++i) {
    double fx_ = 0, fy_ = 0, j[4];
    distort(x, y, fx_, fy_, j);
    const double ex = fx_ - xd, ey = fy_ - yd;
    if (std::abs(ex) + std::abs(ey) < 1e-12 * (1 + std::abs(xd) + std::abs(yd))) return true;
    const double det = j[0] * j[3] - j[1] * j[2];
    if (!(std::abs(det) > 1e-300)) return false;
    x -= (j[3] * ex - j[1] * ey) / det;
    y -= (-j[2] * ex + j[0] * ey) / det;
    if (!std::isfinite(x) || !std::isfinite(y)) return false;
  }
  return false;
}

PinholeCamera::PinholeCamera(const Vec3d& position, const Vec3d& lookAt, const Vec3d& up,
                             double hfovDegrees, int width, int height) {
  const Vec3d view = lookAt - position;
  if (!(length(view) > 0)) throw Error("camera: position and look_at must differ");
  if (!(hfovDegrees > 0 && hfovDegrees < 180))
    throw Error("camera: field of view must lie in (0, 180) degrees");
  if (width <= 0 || height <= 0) throw Error("camera: image size must be positive");
  const Vec3d forward = normalize(view);
  Vec3d preferred = length(up) > 0 ? normalize(up) : Vec3d(0, 1, 0);
  if (std::abs(dot(preferred, forward)) > 0.999999) {
    // Looking along the up direction: take the world axis least aligned with the view.
    const double ax = std::abs(forward.x), ay = std::abs(forward.y), az = std::abs(forward.z);
    preferred =
        (az <= ax && az <= ay) ? Vec3d(0, 0, 1) : (ax <= ay ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0));
  }
  // Left-handed image frame: right = up x forward, so that +y up and +z forward give +x right.
  const Vec3d right = normalize(cross(preferred, forward));
  const Vec3d imageUp = cross(forward, right);
  // The same camera in OpenCV's terms: rows of R are the camera's x (right), y (down) and z
  // (forward) axes; the focal length puts the horizontal field of view across the width.
  cal_.fx = cal_.fy = 0.5 * width / std::tan(0.5 * hfovDegrees * kPi / 180.0);
  cal_.cx = 0.5 * width - 0.5;
  cal_.cy = 0.5 * height - 0.5;
  cal_.R = {{{right.x, right.y, right.z},
             {-imageUp.x, -imageUp.y, -imageUp.z},
             {forward.x, forward.y, forward.z}}};
  const Vector3d rp = multiply(cal_.R, {position.x, position.y, position.z});
  cal_.t = Vec3d(-rp[0], -rp[1], -rp[2]);
  finish();
}

PinholeCamera::PinholeCamera(const CameraCalibration& calibration, int width, int height)
    : cal_(calibration) {
  if (width <= 0 || height <= 0) throw Error("camera: image size must be positive");
  if (!(cal_.fx > 0 && cal_.fy > 0 && std::isfinite(cal_.fx) && std::isfinite(cal_.fy)))
    throw Error("camera: focal lengths must be positive");
  finish();
}

void PinholeCamera::finish() {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) cameraToWorld_[i][j] = cal_.R[j][i];
  // Centre of projection: R C + t = 0, so C = -R^T t.
  const Vector3d c = multiply(cameraToWorld_, {cal_.t.x, cal_.t.y, cal_.t.z});
  position_ = Vec3d(-c[0], -c[1], -c[2]);
  forward_ = Vec3d(cal_.R[2][0], cal_.R[2][1], cal_.R[2][2]);
  right_ = Vec3d(cal_.R[0][0], cal_.R[0][1], cal_.R[0][2]);
  up_ = Vec3d(-cal_.R[1][0], -cal_.R[1][1], -cal_.R[1][2]);
  distorted_ = cal_.distorted();
}

void PinholeCamera::setThinLens(double apertureRadius, double focusDistance) {
  if (!(apertureRadius >= 0 && focusDistance > 0))
    throw Error("camera: a thin lens needs an aperture radius >= 0 and a focus distance > 0");
  lensRadius_ = apertureRadius;
  focusDistance_ = focusDistance;
}

Ray PinholeCamera::generateRay(double x, double y, double lensX, double lensY) const {
  Vec3d origin, direction;
  generateRay(x, y, lensX, lensY, origin, direction);
  Ray r;
  r.o = Vec3(origin);
  r.d = Vec3(direction);
  return r;
}

void PinholeCamera::generateRay(double x, double y, double lensX, double lensY, Vec3d& origin,
                                Vec3d& direction) const {
  // Film position to OpenCV pixel coordinates (centres at integers), then to normalised
  // coordinates, undistorted when the lens distorts.
  double nx = (x - 0.5 - cal_.cx) / cal_.fx, ny = (y - 0.5 - cal_.cy) / cal_.fy;
  if (distorted_) {
    double ux = nx, uy = ny;
    if (cal_.undistort(nx, ny, ux, uy)) nx = ux, ny = uy; // checked over the image at load
  }
  Vector3d dCam{nx, ny, 1.0};
  origin = position_;
  if (lensRadius_ > 0) {
    // Thin lens (camera space): every ray through the pinhole direction's point on the plane of
    // focus z = focusDistance, from a point of the aperture disk in the plane z = 0.
    const double lx = lensRadius_ * lensX, ly = lensRadius_ * lensY;
    dCam = {nx * focusDistance_ - lx, ny * focusDistance_ - ly, focusDistance_};
    const Vector3d o = multiply(cameraToWorld_, {lx, ly, 0.0});
    origin = position_ + Vec3d(o[0], o[1], o[2]);
  }
  const Vector3d d = multiply(cameraToWorld_, dCam);
  direction = normalize(Vec3d(d[0], d[1], d[2]));
}

} // namespace nx
