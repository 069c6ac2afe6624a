// Solid-angle sampling of triangles (Arvo 1995): the solid angle against closed forms and an
// independent quadrature, the sampled directions against the density 1 / Omega (chi-square over
// sub-triangles), near, far, grazing and nearly in the triangle's plane.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/math_util.h"
#include "integrators/lights/spherical_triangle.h"
#include "support/statistics.h"

namespace nx {
namespace {

// Solid angle of triangle t from p by the midpoint rule over an n x n barycentric subdivision:
// the integral of |cos theta_l| / d^2 over its area (independent of the closed form).
double quadratureSolidAngle(const TriangleShape& t, const Vec3d& p, int n = 64) {
  const Vec3d e1 = t.b - t.a, e2 = t.c - t.a, nd = cross(e1, e2);
  const double area = 0.5 * length(nd);
  const Vec3d normal = nd * (1 / length(nd));
  double sum = 0;
  int cells = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n - i; ++j)
      for (int up = 0; up < (i + j < n - 1 ? 2 : 1); ++up) {
        // Centroid of the small triangle (upright, or inverted for up = 1).
        const double b1 = up == 0 ? (i + 1.0 / 3) / n : (i + 2.0 / 3) / n;
        const double b2 = up == 0 ? (j + 1.0 / 3) / n : (j + 2.0 / 3) / n;
        const Vec3d q = t.a + e1 * b1 + e2 * b2, d = q - p;
        const double d2 = dot(d, d);
        sum += std::abs(dot(normal, d)) / (d2 * std::sqrt(d2));
        ++cells;
      }
  return sum * area / cells;
}

TEST(SphericalTriangle, SolidAngleMatchesClosedFormsAndQuadrature) {
  // The octant: pi / 2.
  EXPECT_NEAR(sphericalTriangleArea(Vec3d(1, 0, 0), Vec3d(0, 1, 0), Vec3d(0, 0, 1)), kPi / 2,
              1e-12);
  // An a x b rectangle (two triangles) seen from h below one corner:
  // atan(ab / (h sqrt(a^2 + b^2 + h^2))).
  const double a = 0.7, b = 1.3, h = 0.4;
  const TriangleShape corner{Vec3d(0, h, 0), Vec3d(a, h, 0), Vec3d(0, h, b)};
  const TriangleShape opposite{Vec3d(a, h, 0), Vec3d(a, h, b), Vec3d(0, h, b)};
  EXPECT_NEAR(sphericalTriangle(corner, Vec3d(0, 0, 0)).solidAngle +
                  sphericalTriangle(opposite, Vec3d(0, 0, 0)).solidAngle,
              std::atan(a * b / (h * std::sqrt(a * a + b * b + h * h))), 1e-12);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(-1, 1);
  for (int k = 0; k < 20; ++k) {
    const TriangleShape t{Vec3d(x(rng), 1 + x(rng), x(rng)), Vec3d(x(rng), 1 + x(rng), x(rng)),
                          Vec3d(x(rng), 1 + x(rng), x(rng))};
    const Vec3d p(0.3 * x(rng), -1, 0.3 * x(rng));
    const double q = quadratureSolidAngle(t, p, 256);
    EXPECT_NEAR(sphericalTriangle(t, p).solidAngle, q, 1e-4 * q) << k;
  }
  // A corner at the point itself, or an edge-on triangle: no solid angle.
  EXPECT_EQ(sphericalTriangle(corner, Vec3d(0, h, 0)).solidAngle, 0);
  EXPECT_NEAR(sphericalTriangle(corner, Vec3d(5, h, 5)).solidAngle, 0, 1e-12);
}

// Index of the sub-triangle (of an n x n barycentric subdivision) containing barycentrics
// (b1, b2); cells numbered as quadratureCells lists them.
int subTriangleOf(double b1, double b2, int n) {
  const int i = std::min(n - 1, std::max(0, static_cast<int>(b1 * n)));
  const int j = std::min(n - 1 - i, std::max(0, static_cast<int>(b2 * n)));
  const double fi = b1 * n - i, fj = b2 * n - j;
  const bool inverted = fi + fj > 1 && i + j < n - 1;
  return (i * n + j) * 2 + (inverted ? 1 : 0);
}

// The sub-triangles of an n x n barycentric subdivision of t at the indices subTriangleOf
// gives them, (i n + j) 2 + up (up = 1: the inverted one); indices without a cell hold a
// degenerate triangle (all corners at t.a).
std::vector<TriangleShape> subTriangles(const TriangleShape& t, int n) {
  const Vec3d e1 = (t.b - t.a) * (1.0 / n), e2 = (t.c - t.a) * (1.0 / n);
  std::vector<TriangleShape> cells(static_cast<size_t>(2 * n * n), {t.a, t.a, t.a});
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n - i; ++j) {
      const Vec3d o = t.a + e1 * double(i) + e2 * double(j);
      cells[static_cast<size_t>((i * n + j) * 2)] = {o, o + e1, o + e2};
      if (i + j < n - 1)
        cells[static_cast<size_t>((i * n + j) * 2 + 1)] = {o + e1, o + e1 + e2, o + e2};
    }
  return cells;
}

// Directions drawn by sampleSphericalTriangle land on each sub-triangle of a 6 x 6 subdivision
// in proportion to its solid angle (the closed form the test above checks; the sub-triangles'
// sum to the whole's): chi-square, for a point close to a large
// triangle (Omega about 1.4 sr), one far from it (1e-4 sr), one seeing it at a grazing angle and
// one nearly inside its plane under it (about 2 pi).
TEST(SphericalTriangle, SamplesAreUniformInSolidAngle) {
  const TriangleShape t{Vec3d(-1, 1, -0.6), Vec3d(1.2, 1.1, -0.4), Vec3d(0.1, 0.9, 1.3)};
  const Vec3d points[] = {Vec3d(0, 0.4, 0), Vec3d(0.5, 150, 0.2), Vec3d(6, 0.7, 0),
                          Vec3d(0.1, 1.0 - 1e-2, 0.1)};
  const int n = 6, samples = 100000;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const Vec3d e1 = t.b - t.a, e2 = t.c - t.a;
  for (const Vec3d& p : points) {
    const SphericalTriangle s = sphericalTriangle(t, p);
    ASSERT_GT(s.solidAngle, 0);
    // Expected share of each sub-triangle: its solid angle over the whole's.
    const std::vector<TriangleShape> cells = subTriangles(t, n);
    std::vector<double> expected(cells.size(), 0), observed = expected;
    double total = 0;
    for (size_t k = 0; k < cells.size(); ++k)
      total += expected[k] = sphericalTriangle(cells[k], p).solidAngle;
    EXPECT_NEAR(total, s.solidAngle, 1e-3 * s.solidAngle);
    for (double& e : expected) e *= samples / total;
    for (int k = 0; k < samples; ++k) {
      Vec3d w;
      ASSERT_TRUE(sampleSphericalTriangle(s, {u01(rng), u01(rng)}, w));
      EXPECT_NEAR(length(w), 1.0, 1e-9);
      // Where w meets the triangle's plane, in barycentrics (Moeller-Trumbore).
      const Vec3d pv = cross(w, e2), sv = p - t.a, qv = cross(sv, e1);
      const double det = dot(e1, pv);
      const double b1 = dot(sv, pv) / det, b2 = dot(w, qv) / det, dist = dot(e2, qv) / det;
      ASSERT_GT(dist, 0);
      ASSERT_GT(b1, -1e-6);
      ASSERT_GT(b2, -1e-6);
      ASSERT_LT(b1 + b2, 1 + 1e-6);
      observed[static_cast<size_t>(subTriangleOf(b1, b2, n))] += 1;
    }
    const auto [stat, dof] = test::chiSquare(observed, expected);
    EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << "Omega " << s.solidAngle;
  }
}

// The inverse of the sampling map returns the square's point a direction came from, so the
// cosine-warped density (which needs it at BSDF-sampled hits) is evaluated where it was drawn.
TEST(SphericalTriangle, InverseSampleRoundTrips) {
  const TriangleShape t{Vec3d(-1, 1, -0.6), Vec3d(1.2, 1.1, -0.4), Vec3d(0.1, 0.9, 1.3)};
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (const Vec3d& p : {Vec3d(0, 0.4, 0), Vec3d(0.5, 150, 0.2), Vec3d(6, 0.7, 0)}) {
    const SphericalTriangle s = sphericalTriangle(t, p);
    for (int k = 0; k < 2000; ++k) {
      const Sample2 u{0.001f + 0.998f * u01(rng), 0.001f + 0.998f * u01(rng)};
      Vec3d w;
      ASSERT_TRUE(sampleSphericalTriangle(s, u, w));
      const Sample2 back = invertSphericalTriangleSample(s, w);
      EXPECT_NEAR(back.u, u.u, 2e-4) << s.solidAngle;
      EXPECT_NEAR(back.v, u.v, 2e-4) << s.solidAngle;
    }
  }
}

// BilinearDensity::sample follows BilinearDensity::pdf: chi-square over a 16 x 16 grid whose
// expected counts integrate the density over each cell (bilinear: exact at the cell's
// centre), for weights from even to 1:100.
TEST(SphericalTriangle, BilinearWarpFollowsItsDensity) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (const BilinearDensity d : {BilinearDensity{1, 1, 1, 1}, BilinearDensity{0.01, 0.5, 1, 0.2},
                                  BilinearDensity{1, 0.01, 0.01, 1}}) {
    const int g = 16, n = 200000;
    std::vector<double> obs(g * g, 0), exp(g * g);
    for (int j = 0; j < g; ++j)
      for (int i = 0; i < g; ++i)
        exp[static_cast<size_t>(j * g + i)] =
            n * d.pdf({static_cast<float>((i + 0.5) / g), static_cast<float>((j + 0.5) / g)}) /
            (g * g);
    for (int k = 0; k < n; ++k) {
      const Sample2 x = d.sample({u01(rng), u01(rng)});
      ASSERT_GE(x.u, 0);
      ASSERT_LT(x.u, 1);
      ASSERT_GE(x.v, 0);
      ASSERT_LT(x.v, 1);
      obs[static_cast<size_t>(static_cast<int>(x.v * g) * g + static_cast<int>(x.u * g))] += 1;
    }
    const auto [stat, dof] = test::chiSquare(obs, exp);
    EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << d.w00 << " " << d.w10;
  }
}

// Directions drawn through the cosine warp (the square's point from cosineWarp, then the
// spherical map) follow the density the light sampler's pdf uses for them,
// cosineWarp.pdf(invert(w)) / Omega: chi-square over sub-triangles whose expected share is that
// density integrated over each (midpoint rule in solid angle, 24 x 24 per sub-triangle), for a
// receiver facing the triangle and one nearly edge-on to it.
TEST(SphericalTriangle, CosineWarpedSamplesFollowTheirDensity) {
  const TriangleShape t{Vec3d(-1, 1, -0.6), Vec3d(1.2, 1.1, -0.4), Vec3d(0.1, 0.9, 1.3)};
  const Vec3d p(0.2, 0.3, 0.1);
  const SphericalTriangle s = sphericalTriangle(t, p);
  const Vec3d e1 = t.b - t.a, e2 = t.c - t.a;
  const int n = 5, samples = 100000, q = 24;
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (const Vec3d normal : {Vec3d(0, 1, 0), normalize(Vec3d(1, 0.05, 0.2))}) {
    const BilinearDensity warp = cosineWarp(s, normal);
    const auto density = [&](const Vec3d& w) {
      return warp.pdf(invertSphericalTriangleSample(s, w)) / s.solidAngle;
    };
    // Each sub-triangle's mass: the density at the centroids of its own q x q subdivision.
    const std::vector<TriangleShape> cells = subTriangles(t, n);
    std::vector<double> expected(cells.size(), 0), observed = expected;
    double total = 0;
    for (size_t k = 0; k < cells.size(); ++k)
      for (const TriangleShape& cell : subTriangles(cells[k], q)) {
        const Vec3d mid = normalize((cell.a + cell.b + cell.c) * (1.0 / 3) - p);
        const double mass = density(mid) * sphericalTriangle(cell, p).solidAngle;
        expected[k] += mass;
        total += mass;
      }
    EXPECT_NEAR(total, 1.0, 2e-3);
    for (double& e : expected) e *= samples / total;
    for (int k = 0; k < samples; ++k) {
      const Sample2 u = warp.sample({u01(rng), u01(rng)});
      Vec3d w;
      ASSERT_TRUE(sampleSphericalTriangle(s, u, w));
      const Vec3d pv = cross(w, e2), sv = p - t.a, qv = cross(sv, e1);
      const double det = dot(e1, pv);
      observed[static_cast<size_t>(subTriangleOf(dot(sv, pv) / det, dot(w, qv) / det, n))] += 1;
    }
    const auto [stat, dof] = test::chiSquare(observed, expected);
    EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << normal.x;
  }
}

} // namespace
} // namespace nx
