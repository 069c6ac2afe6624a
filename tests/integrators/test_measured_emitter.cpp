// Lamps as measured on area emitters: irradiance on the axis at a distance and total flux
// per unit radiance against closed forms and quadrature, and rendered.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "accel/kinds/triangle.h"
#include "core/error.h"
#include "integrators/lights/measured_emitter.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "io/mesh_reader.h"
#include "support/errors.h"
#include "support/statistics.h"

namespace nx {
namespace {

constexpr double kPi = std::numbers::pi;

// A quad as its kind builds it: two triangles.
TriangleMesh quadMesh(const Vec3d& o, const Vec3d& u, const Vec3d& v) {
  return TriangleMesh::fromTriangles({{o, o + u, o + u + v}, {o, o + u + v, o + v}});
}

// Irradiance per radiance at x (unit normal n) from a triangle, by a midpoint rule on a
// k x k subdivision: the integral of cos_e cos_r / r^2 over its area (independent of Lambert's
// formula).
double quadrature(const TriangleShape& t, const Vec3d& x, const Vec3d& n, int k) {
  const Vec3d e1 = t.b - t.a, e2 = t.c - t.a, ng = cross(e1, e2);
  const double cellArea = length(ng) / 2 / (k * k);
  const Vec3d nn = normalize(ng);
  double sum = 0;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k - i; ++j)
      for (int up = 0; up < (j < k - i - 1 ? 2 : 1); ++up) {
        // Centroids of the small triangles (upright and inverted) of the subdivision.
        const double s = up ? (i + 2.0 / 3) / k : (i + 1.0 / 3) / k;
        const double r = up ? (j + 2.0 / 3) / k : (j + 1.0 / 3) / k;
        const Vec3d p = t.a + e1 * s + e2 * r;
        const Vec3d w = p - x;
        const double d2 = dot(w, w), d = std::sqrt(d2);
        sum += std::abs(dot(w, nn)) / d * std::max(0.0, dot(w, n)) / d / d2 * cellArea;
      }
  return sum;
}

TEST(MeasuredEmitter, SphereOnAxisIsPiRSquaredOverDSquared) {
  const SphereShape s{{1, 2, 3}, 0.5};
  for (double d : {0.6, 2.0, 50.0})
    EXPECT_NEAR(axialIrradiancePerRadiance(s, d, "t"), kPi * 0.25 / (d * d), 1e-12);
  EXPECT_NE(test::errorMessage([&] {
              axialIrradiancePerRadiance(s, 0.4, "t.scn:3");
            }).find("t.scn:3: expected a measuring distance beyond the sphere's radius 0.5"),
            std::string::npos);
  EXPECT_NEAR(fluxPerRadiance(s, "t"), 4 * kPi * kPi * 0.25, 1e-12);
}

TEST(MeasuredEmitter, RectangleOnAxisIsItsViewFactor) {
  // A rectangle a x b seen from distance d on its central normal: E / L = 2 [X / sqrt(1 + X^2)
  // atan(Y / sqrt(1 + X^2)) + Y / sqrt(1 + Y^2) atan(X / sqrt(1 + Y^2))], X = a / 2d,
  // Y = b / 2d (four corner view factors; Howell's catalogue, case B-3). Small: A / d^2.
  for (const auto& [a, b, d] :
       {std::array{2.0, 1.0, 0.5}, std::array{0.3, 0.3, 10.0}, std::array{4.0, 0.1, 1.0}}) {
    const double X = a / (2 * d), Y = b / (2 * d);
    const double want = 2 * (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
                             Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y)));
    // Placed obliquely: rotated 30 degrees about z, tilted, moved.
    const Vec3d u = Vec3d(std::cos(0.5), std::sin(0.5), 0.3) * 1.0;
    const Vec3d un = normalize(u), vn = normalize(cross(Vec3d(0.2, -0.1, 1), un));
    const TriangleMesh m = quadMesh({3, -1, 2}, un * a, vn * b);
    // (the mesh holds its corners in single precision)
    EXPECT_NEAR(axialIrradiancePerRadiance(m, d, "t"), want, 1e-6 * want) << a << " " << b;
    EXPECT_NEAR(fluxPerRadiance(m, "t"), 2 * kPi * a * b, 1e-6 * a * b); // two faces
  }
}

TEST(MeasuredEmitter, TriangleOnAxisAgreesWithQuadrature) {
  const TriangleShape t{{0, 0, 0}, {2, 0, 0}, {0.5, 1.5, 0}};
  const Vec3d c = (t.a + t.b + t.c) / 3.0;
  for (double d : {0.3, 1.0, 5.0}) {
    const double got = axialIrradiancePerRadiance(t, d, "t");
    const double want = quadrature(t, c + Vec3d(0, 0, d), {0, 0, -1}, 600);
    EXPECT_NEAR(got, want, 2e-4 * want) << d;
  }
}

TEST(MeasuredEmitter, PlanesAndCurvedMeshesHaveNoAxis) {
  EXPECT_NE(test::errorMessage([] {
              axialIrradiancePerRadiance(PlaneShape{}, 1, "t");
            }).find("found a plane"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([] { fluxPerRadiance(PlaneShape{}, "t"); }).find("found a plane"),
            std::string::npos);
  const TriangleMesh cube = readMeshFile(std::string(NX_TEST_DATA_DIR) + "/media/cube.obj").mesh;
  EXPECT_NE(test::errorMessage([&] {
              axialIrradiancePerRadiance(cube, 1, "t");
            }).find("found a curved or folded mesh (give its total flux with quantity"),
            std::string::npos);
  // A closed mesh's inward light never leaves it: its flux is pi A (the cube [-1, 1]^3: 24).
  EXPECT_NEAR(fluxPerRadiance(cube, "t"), kPi * 24, 1e-9);
}

// The radiance of a small white diffuse receiver facing the emitter at its measuring point:
// E / pi, E the irradiance the scene file gave (3 per nm), for a quad at="2" and, as
// quantity="flux" for a sphere, E = flux / (4 pi d^2) at distance d.
TEST(MeasuredEmitter, RendersTheMeasuredIrradiance) {
  auto scene = [](const std::string& emitter, double d) {
    const std::string z = std::to_string(d);
    return "<scene><settings><xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><sampl>64"
           "</sampl><depth>1</depth><bands>450:650:100</bands></settings><camera>"
           "<position>0.8,0,0.6</position><look_at>0,0," +
           z + "</look_at><fov>0.2</fov></camera>" + emitter + "<quad><origin>-0.02,-0.02," + z +
           "</origin><edge_u>0.04,0,0</edge_u><edge_v>0,0.04,0</edge_v><material>matte</material>"
           "<reflectance>1</reflectance></quad></scene>";
  };
  const double pi = kPi;
  struct Case {
    std::string emitter;
    double d, irradiance;
  };
  for (const Case& c : {Case{"<quad><origin>-0.5,-0.25,0</origin><edge_u>1,0,0</edge_u><edge_v>0,"
                             "0.5,0</edge_v><material>matte</material><emission at=\"2\">3"
                             "</emission></quad>",
                             2, 3},
                        Case{"<sphere><center>0,0,0</center><radius>0.3</radius><material>matte"
                             "</material><emission quantity=\"flux\">3</emission></sphere>",
                             1.5, 3 / (4 * pi * 1.5 * 1.5)}}) {
    const RenderOutput out =
        render(buildRenderScene(parseScene(scene(c.emitter, c.d), "t.scn")), RenderOptions{});
    for (int b = 0; b < out.film.bands().count(); ++b) {
      test::RunningStats st;
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) st.add(out.film.bandMean(x, y, b));
      EXPECT_NEAR(st.mean, c.irradiance / pi, 5 * st.standardError() + 1e-3 * c.irradiance)
          << c.emitter << " band " << b;
    }
  }
  // Both at once, or at="d" on a plane, are refused.
  EXPECT_NE(test::errorMessage([&] {
              parseScene(scene("<sphere><center>0,0,0</center><radius>0.3</radius><material>"
                               "matte</material><emission at=\"2\" quantity=\"flux\">3</emission>"
                               "</sphere>",
                               2),
                         "t.scn");
            })
                .find("t.scn:1: expected either at=\"d\" (irradiance at a distance) or "
                      "quantity=\"flux\" on <emission>, found both"),
            std::string::npos);
}

} // namespace
} // namespace nx
