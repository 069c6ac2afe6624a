// Solid-angle sampling of rectangles (Urena et al. 2013): the solid angle against closed forms,
// the sampled points against the density 1 / Omega and the cosine-warped one (chi-square over
// cells of the rectangle), the inverse map, and which two-triangle meshes are rectangles.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/math_util.h"
#include "integrators/lights/spherical_rectangle.h"
#include "support/statistics.h"

namespace nx {
namespace {

// Solid angle of the cell [s0, s1] x [t0, t1] of rectangle r from p: its two spherical
// triangles (Van Oosterom & Strackee, tested in test_spherical_triangle.cpp).
double cellSolidAngle(const Rectangle& r, double s0, double s1, double t0, double t1,
                      const Vec3d& p) {
  const auto at = [&](double s, double t) { return r.corner + r.edgeX * s + r.edgeY * t; };
  return sphericalTriangle({at(s0, t0), at(s1, t0), at(s1, t1)}, p).solidAngle +
         sphericalTriangle({at(s0, t0), at(s1, t1), at(s0, t1)}, p).solidAngle;
}

// The rectangle's own (s, t) of a point on it.
void rectangleCoordinates(const Rectangle& r, const Vec3d& q, double& s, double& t) {
  const Vec3d d = q - r.corner;
  s = dot(d, r.edgeX) / dot(r.edgeX, r.edgeX);
  t = dot(d, r.edgeY) / dot(r.edgeY, r.edgeY);
}

const Rectangle kTilted{Vec3d(-1, 1, -0.5), Vec3d(1.6, 0.4, 0), Vec3d(0, 0, 1.2)};

TEST(SphericalRectangle, SolidAngleMatchesClosedForms) {
  // An a x b rectangle seen from h below one corner: atan(ab / (h sqrt(a^2 + b^2 + h^2))).
  const double a = 0.7, b = 1.3, h = 0.4;
  const Rectangle corner{Vec3d(0, h, 0), Vec3d(a, 0, 0), Vec3d(0, 0, b)};
  EXPECT_NEAR(sphericalRectangle(corner, Vec3d(0, 0, 0)).solidAngle,
              std::atan(a * b / (h * std::sqrt(a * a + b * b + h * h))), 1e-12);
  // From above (the other side) the same.
  EXPECT_NEAR(sphericalRectangle(corner, Vec3d(0, 2 * h, 0)).solidAngle,
              std::atan(a * b / (h * std::sqrt(a * a + b * b + h * h))), 1e-12);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> x(-1, 1);
  for (int k = 0; k < 50; ++k) {
    const Vec3d p(2 * x(rng), 2 * x(rng), 2 * x(rng));
    const double expected = cellSolidAngle(kTilted, 0, 1, 0, 1, p);
    EXPECT_NEAR(sphericalRectangle(kTilted, p).solidAngle, expected, 1e-9 + 1e-9 * expected) << k;
  }
  // In the rectangle's plane: nothing is seen.
  EXPECT_EQ(sphericalRectangle(corner, Vec3d(2, h, 3)).solidAngle, 0);
}

// Points drawn by sampleSphericalRectangle land in each cell of an 8 x 8 grid over the
// rectangle in proportion to the cell's solid angle: chi-square, from a point close to it
// (about 1.8 sr), one at the smallest solid angle sampled this way (0.01 sr), one seeing it
// at a grazing angle and one nearly in its plane, under it (about 2 pi).
TEST(SphericalRectangle, SamplesAreUniformInSolidAngle) {
  const Vec3d points[] = {Vec3d(0, 0.6, 0.1), Vec3d(0.5, 12.0, 0.2), Vec3d(6, 0.7, 0),
                          Vec3d(-0.2, 1.19, 0.1)};
  const int g = 8, samples = 100000;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (const Vec3d& p : points) {
    const SphericalRectangle s = sphericalRectangle(kTilted, p);
    ASSERT_GT(s.solidAngle, 0);
    std::vector<double> expected(g * g), observed(g * g, 0);
    double total = 0;
    for (int j = 0; j < g; ++j)
      for (int i = 0; i < g; ++i)
        total += expected[static_cast<size_t>(j * g + i)] = cellSolidAngle(
            kTilted, double(i) / g, double(i + 1) / g, double(j) / g, double(j + 1) / g, p);
    EXPECT_NEAR(total, s.solidAngle, 1e-6 * s.solidAngle);
    for (double& e : expected) e *= samples / total;
    for (int k = 0; k < samples; ++k) {
      Vec3d q;
      ASSERT_TRUE(sampleSphericalRectangle(s, {u01(rng), u01(rng)}, q));
      double a, b;
      rectangleCoordinates(kTilted, q, a, b);
      ASSERT_GT(a, -1e-9);
      ASSERT_LT(a, 1 + 1e-9);
      ASSERT_GT(b, -1e-9);
      ASSERT_LT(b, 1 + 1e-9);
      const int i = std::min(g - 1, static_cast<int>(a * g)),
                j = std::min(g - 1, static_cast<int>(b * g));
      observed[static_cast<size_t>(j * g + i)] += 1;
    }
    const auto [stat, dof] = test::chiSquare(observed, expected);
    EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << "Omega " << s.solidAngle;
  }
}

// The inverse of the sampling map returns the square's point a rectangle's point came from.
TEST(SphericalRectangle, InverseSampleRoundTrips) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (const Vec3d& p : {Vec3d(0, 0.6, 0.1), Vec3d(0.5, 12.0, 0.2), Vec3d(6, 0.7, 0)}) {
    const SphericalRectangle s = sphericalRectangle(kTilted, p);
    for (int k = 0; k < 2000; ++k) {
      const Sample2 u{0.001f + 0.998f * u01(rng), 0.001f + 0.998f * u01(rng)};
      Vec3d q;
      ASSERT_TRUE(sampleSphericalRectangle(s, u, q));
      const Sample2 back = invertSphericalRectangleSample(s, q);
      EXPECT_NEAR(back.u, u.u, 2e-4) << s.solidAngle;
      EXPECT_NEAR(back.v, u.v, 2e-4) << s.solidAngle;
    }
  }
}

// Points drawn through the cosine warp follow the density the light sampler's pdf gives them,
// cosineWarp.pdf(invert(q)) / Omega: chi-square over 8 x 8 cells whose expected share is that
// density integrated over each (midpoint rule in solid angle, 16 x 16 per cell), for a receiver
// facing the rectangle and one nearly edge-on to it.
TEST(SphericalRectangle, CosineWarpedSamplesFollowTheirDensity) {
  const Vec3d p(0.2, 0.3, 0.1);
  const SphericalRectangle s = sphericalRectangle(kTilted, p);
  const int g = 8, q = 16, samples = 100000;
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (const Vec3d normal : {Vec3d(0, 1, 0), normalize(Vec3d(1, 0.05, 0.2))}) {
    const BilinearDensity warp = cosineWarp(s, normal);
    std::vector<double> expected(g * g, 0), observed(g * g, 0);
    double total = 0;
    for (int j = 0; j < g * q; ++j)
      for (int i = 0; i < g * q; ++i) {
        const double s0 = double(i) / (g * q), t0 = double(j) / (g * q), h = 1.0 / (g * q);
        const Vec3d mid =
            kTilted.corner + kTilted.edgeX * (s0 + h / 2) + kTilted.edgeY * (t0 + h / 2);
        const double mass = warp.pdf(invertSphericalRectangleSample(s, mid)) / s.solidAngle *
                            cellSolidAngle(kTilted, s0, s0 + h, t0, t0 + h, p);
        expected[static_cast<size_t>((j / q) * g + i / q)] += mass;
        total += mass;
      }
    EXPECT_NEAR(total, 1.0, 2e-3);
    for (double& e : expected) e *= samples / total;
    for (int k = 0; k < samples; ++k) {
      Vec3d point;
      ASSERT_TRUE(sampleSphericalRectangle(s, warp.sample({u01(rng), u01(rng)}), point));
      double a, b;
      rectangleCoordinates(kTilted, point, a, b);
      observed[static_cast<size_t>(std::min(g - 1, static_cast<int>(b * g)) * g +
                                   std::min(g - 1, static_cast<int>(a * g)))] += 1;
    }
    const auto [stat, dof] = test::chiSquare(observed, expected);
    EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << normal.x;
  }
}

TriangleMesh twoTriangles(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                          bool otherDiagonal = false) {
  TriangleMesh m;
  const uint32_t ia = m.addVertex(a), ib = m.addVertex(b), ic = m.addVertex(c), id = m.addVertex(d);
  if (otherDiagonal) {
    m.addTriangle(ia, ib, id);
    m.addTriangle(ib, ic, id);
  } else {
    m.addTriangle(ia, ib, ic);
    m.addTriangle(ia, ic, id);
  }
  return m;
}

// Meshes of two triangles that form a rectangle are found whichever diagonal they share and
// wherever the rectangle lies (float corners far from the origin); parallelograms, kites,
// separate triangles and other triangle counts are not rectangles.
TEST(SphericalRectangle, RectanglesAreRecognised) {
  const Vec3 a(-0.4f, 1.1f, -0.3f), u(0.8f, 0, 0), v(0, 0, 0.8f);
  for (bool other : {false, true}) {
    const auto r = rectangleOf(twoTriangles(a, a + u, a + u + v, a + v, other));
    ASSERT_TRUE(r.has_value()) << other;
    EXPECT_NEAR(length(cross(r->edgeX, r->edgeY)), 0.64, 1e-6);
    EXPECT_NEAR(dot(r->edgeX, r->edgeY), 0, 1e-6);
  }
  const Vec3 far(1000.3f, -2000.7f, 512.1f), tu(0.3f, 0.4f, 0), tv(-0.8f, 0.6f, 0.5f);
  EXPECT_TRUE(rectangleOf(twoTriangles(far, far + tu, far + tu + tv, far + tv)).has_value());
  EXPECT_FALSE(
      rectangleOf(twoTriangles(a, a + u, a + u + v + Vec3(0.1f, 0, 0), a + v + Vec3(0.1f, 0, 0)))
          .has_value()); // a parallelogram
  EXPECT_FALSE(
      rectangleOf(twoTriangles(a, a + u, a + u + v * 1.5f, a + v)).has_value()); // a trapezoid
  TriangleMesh apart =
      TriangleMesh::fromTriangles({{Vec3d(0, 0, 0), Vec3d(1, 0, 0), Vec3d(1, 1, 0)},
                                   {Vec3d(0, 0, 1), Vec3d(1, 1, 1), Vec3d(0, 1, 1)}});
  EXPECT_FALSE(rectangleOf(apart).has_value());
  TriangleMesh one =
      TriangleMesh::fromTriangles({{Vec3d(0, 0, 0), Vec3d(1, 0, 0), Vec3d(1, 1, 0)}});
  EXPECT_FALSE(rectangleOf(one).has_value());
}

} // namespace
} // namespace nx
