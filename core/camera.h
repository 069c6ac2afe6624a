#pragma once
// The camera: OpenCV's pinhole model with Brown-Conrady distortion, given by a calibration
// (cv::calibrateCamera / cv::solvePnP output) or by Niixtracer's look-at form, which is turned
// into the same K, R, t.

#include <array>

#include "core/matrix3.h"
#include "core/ray.h"
#include "core/vec3.h"

namespace nx {

/// A calibrated camera as OpenCV describes it. Pixel centres at integer coordinates; camera
/// axes x right, y down, z forward; x_cam = R x_world + t; distortion in OpenCV's order.
struct CameraCalibration {
  double fx = 1, fy = 1, cx = 0, cy = 0;        ///< intrinsics, pixels
  Matrix3 R{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}; ///< world-to-camera rotation
  Vec3d t;                                      ///< world-to-camera translation
  std::array<double, 5> distortion{};           ///< k1, k2, p1, p2, k3

  /// True when some distortion coefficient is not zero.
  bool distorted() const;
  /// OpenCV's forward model: normalised undistorted (x, y) to normalised distorted (xd, yd),
  /// with the Jacobian d(xd, yd) / d(x, y) if `jacobian` is given (row-major 2x2).
  void distort(double x, double y, double& xd, double& yd, double* jacobian = nullptr) const;
  /// Inverts distort() by Newton's method (as cv::undistortPoints inverts it, iteratively);
  /// false if it does not converge to 1e-12.
  bool undistort(double xd, double yd, double& x, double& y) const;
};

/// A pinhole camera with optional lens distortion.
class PinholeCamera {
public:
  /// Camera at `position` looking at `lookAt`; `up` is the preferred up direction (replaced
  /// by the world axis least aligned with the view when parallel to it); horizontal field
  /// of view in degrees (0, 180); image aspect = width / height. Convention (Niixtracer's, like
  /// pbrt's): looking along +z with +y up, +x is on the right of the image.
  PinholeCamera(const Vec3d& position, const Vec3d& lookAt, const Vec3d& up, double hfovDegrees,
                int width, int height);
  /// A calibrated camera for a width x height image (R must be a rotation).
  PinholeCamera(const CameraCalibration& calibration, int width, int height);

  /// Primary ray through film position (x, y) in pixels: (0, 0) is the top-left corner of the
  /// top-left pixel (whose centre, OpenCV's (0, 0), is at (0.5, 0.5)), x grows to the right and
  /// y downwards. Directions are unit length. With a thin lens, (lensX, lensY) is the point of
  /// the unit disk the ray leaves the lens from (ignored by a pinhole).
  Ray generateRay(double x, double y, double lensX = 0, double lensY = 0) const;
  /// generateRay in double precision: the origin and the unit direction.
  void generateRay(double x, double y, double lensX, double lensY, Vec3d& origin,
                   Vec3d& direction) const;

  /// Makes the pinhole a thin lens of the given aperture radius, focused at `focusDistance`
  /// along the optical axis (both in scene units; radius 0: a pinhole).
  void setThinLens(double apertureRadius, double focusDistance);
  /// True for a thin lens (a ray then needs a point on the lens).
  bool hasLens() const { return lensRadius_ > 0; }
  /// Aperture radius and focus distance (scene units).
  double lensRadius() const { return lensRadius_; }
  double focusDistance() const { return focusDistance_; }

  /// The calibration (for a look-at camera, its equivalent K, R, t).
  const CameraCalibration& calibration() const { return cal_; }
  /// Centre of projection in world space.
  const Vec3d& position() const { return position_; }
  /// Unit forward vector (the optical axis).
  const Vec3d& forward() const { return forward_; }
  /// Unit vector to the right of the image (the camera's x axis).
  const Vec3d& right() const { return right_; }
  /// Unit vector to the top of the image (minus the camera's y axis).
  const Vec3d& up() const { return up_; }

private:
  void finish(); // derived quantities from cal_
  CameraCalibration cal_;
  Vec3d position_, forward_, right_, up_;
  Matrix3 cameraToWorld_; ///< R transposed
  bool distorted_ = false;
  double lensRadius_ = 0, focusDistance_ = 1;
};

} // namespace nx
