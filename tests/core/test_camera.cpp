#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/camera.h"
#include "support/opencv_projection.h"

namespace nx {
namespace {

// Distance of X from the ray's line, relative to its distance from the ray's origin.
double missRelative(const Ray& r, const Vec3d& X) {
  const Vec3d o(r.o.x, r.o.y, r.o.z), d = normalize(Vec3d(r.d.x, r.d.y, r.d.z));
  const Vec3d p = X - o;
  return length(p - d * dot(p, d)) / length(p);
}

// Known 3D points seen by a calibrated camera (a rotated pose, off-centre principal point,
// unequal focal lengths), with and without distortion: the ray through the pixel where
// OpenCV projects each point passes through the point.
TEST(Camera, CalibratedRaysPassThroughOpenCvProjections) {
  CameraCalibration cal;
  cal.fx = 812.5, cal.fy = 790.25, cal.cx = 331.7, cal.cy = 251.2;
  cal.R = test::rodrigues(Vec3d(0.21, -0.37, 0.08));
  cal.t = Vec3d(0.3, -0.2, 4.5);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const std::array<double, 5> dist :
       {std::array<double, 5>{}, std::array<double, 5>{-0.21, 0.07, 0.0012, -0.0009, 0.013}}) {
    cal.distortion = dist;
    const PinholeCamera cam(cal, 640, 480);
    int seen = 0;
    for (int i = 0; i < 2000; ++i) {
      // Points in front of the camera: camera-space depth 2-8, within the field of view.
      const Vector3d pc{u(rng) * 2.0, u(rng) * 1.5, 5 + 3 * u(rng)};
      const Vector3d q{pc[0] - cal.t.x, pc[1] - cal.t.y, pc[2] - cal.t.z};
      Matrix3 rt{};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) rt[a][b] = cal.R[b][a];
      const Vector3d w = multiply(rt, q);
      const Vec3d X(w[0], w[1], w[2]);
      double px = 0, py = 0;
      test::projectOpenCv(cal, X, px, py);
      if (px < -0.5 || px > 639.5 || py < -0.5 || py > 479.5) continue;
      ++seen;
      // Film position: OpenCV's pixel centre (0, 0) is at (0.5, 0.5) on the film.
      EXPECT_LT(missRelative(cam.generateRay(px + 0.5, py + 0.5), X), 2e-6)
          << "pixel " << px << "," << py << " k1 " << dist[0];
    }
    EXPECT_GT(seen, 500);
  }
}

// The look-at form is the same camera as before it became a calibration: the old formula.
TEST(Camera, LookAtFormKeepsItsRays) {
  const Vec3d pos(1, 2, -3), at(0, 0.5, 1), up(0.1, 1, 0);
  const PinholeCamera cam(pos, at, up, 50, 320, 200);
  const Vec3d f = normalize(at - pos), r = normalize(cross(normalize(up), f)), v = cross(f, r);
  const double tx = std::tan(25 * 3.14159265358979323846 / 180), ty = tx * 200 / 320;
  for (double x : {0.0, 17.25, 160.0, 320.0})
    for (double y : {0.0, 99.5, 200.0}) {
      const Vec3d d = normalize(f + r * ((2 * x / 320 - 1) * tx) + v * ((1 - 2 * y / 200) * ty));
      const Ray ray = cam.generateRay(x, y);
      EXPECT_NEAR(ray.d.x, d.x, 1e-6);
      EXPECT_NEAR(ray.d.y, d.y, 1e-6);
      EXPECT_NEAR(ray.d.z, d.z, 1e-6);
      EXPECT_NEAR(ray.o.x, 1.0f, 1e-6f);
    }
}

// Distortion and its inverse agree (Newton's method converges to the pre-image).
TEST(Camera, UndistortInvertsDistort) {
  CameraCalibration cal;
  cal.distortion = {-0.28, 0.09, 0.001, -0.0015, -0.01};
  for (double x = -0.6; x <= 0.6; x += 0.05)
    for (double y = -0.45; y <= 0.45; y += 0.05) {
      double xd = 0, yd = 0, bx = 0, by = 0;
      cal.distort(x, y, xd, yd);
      ASSERT_TRUE(cal.undistort(xd, yd, bx, by));
      EXPECT_NEAR(bx, x, 1e-11);
      EXPECT_NEAR(by, y, 1e-11);
    }
}

} // namespace
} // namespace nx
