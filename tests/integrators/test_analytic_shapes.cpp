// Boxes, disks and cylinders against closed forms: silhouettes (projected areas from a grid of
// parallel rays), exact hits on the surface, a disk light's irradiance on its axis and the
// chi-square of its sampling, a cylinder light sampled as BSDF sampling finds it, and the
// furnace inside the closed ones.

#include <gtest/gtest.h>

#include "accel/shape_kinds.h"
#include "core/frame.h"
#include "core/math_util.h"
#include "integrators/lights/light_sampler.h"
#include "integrators/render_scene.h"
#include "integrators/sampling.h"
#include "integrators/scene_reader.h"
#include "support/direction_chi_square.h"
#include "support/flat_wavelengths.h"
#include "support/light_pdf.h"
#include "support/render_checks.h"
#include "support/statistics.h"

namespace nx {
namespace {

const std::string kSettings = "<xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode>";
const std::string kCamera = "<position>0,0,-50</position><look_at>0,0,0</look_at>";

RenderScene sceneOf(const std::string& body) {
  return buildRenderScene(parseScene(sceneText(kSettings, kCamera, body), "t.scn"));
}

// The area a grid of parallel rays along `dir` finds covered, and the largest error of the
// count: every cell the outline crosses (perimeter / cell) may be miscounted.
struct Silhouette {
  double area, tolerance;
};
Silhouette silhouette(const GeometryScene& g, const Vec3d& dir, double halfWidth,
                      double perimeterBound) {
  const int n = 600;
  const AxisFrame f = AxisFrame::of(normalize(dir));
  const double cell = 2 * halfWidth / n;
  int hits = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3d o = f.s * (-halfWidth + (i + 0.5) * cell) +
                      f.t * (-halfWidth + (j + 0.5) * cell) - f.n * 100.0;
      Ray r;
      r.o = Vec3(o);
      r.d = Vec3(f.n);
      SurfaceHit h;
      hits += g.intersect(r, h);
    }
  return {hits * cell * cell, perimeterBound * cell * 1.5};
}

TEST(AnalyticShapes, BoxSilhouetteIsItsProjectedArea) {
  const RenderScene s = sceneOf("<box><center>0.1,0,0</center><size>1,2,0.5</size>"
                                "<material>matte</material><reflectance>0.5</reflectance></box>");
  for (const Vec3d d : {Vec3d(0, 0, 1), Vec3d(1, 1, 1), Vec3d(0.3, -2, 0.7)}) {
    const Vec3d u = normalize(d);
    // |d_x| b c + |d_y| a c + |d_z| a b for edges a, b, c along x, y, z
    const double expected = std::abs(u.x) * 2 * 0.5 + std::abs(u.y) * 1 * 0.5 + std::abs(u.z) * 2;
    const Silhouette got = silhouette(*s.geometry, d, 1.6, 2 * (1 + 2 + 0.5) * 2);
    EXPECT_NEAR(got.area, expected, got.tolerance) << d.x << " " << d.y << " " << d.z;
  }
}

TEST(AnalyticShapes, CylinderAndDiskSilhouettesAreTheirProjectedAreas) {
  const double r = 0.4, h = 1.5;
  const RenderScene s = sceneOf(
      "<cylinder><p0>0,-0.75,0</p0><p1>0,0.75,0</p1><radius>0.4</radius><capped>true</capped>"
      "<material>matte</material><reflectance>0.5</reflectance></cylinder>");
  const RenderScene disk =
      sceneOf("<disk><center>0,0,0</center><normal>0,1,0</normal><radius>0.4</radius>"
              "<material>matte</material><reflectance>0.5</reflectance></disk>");
  for (const double theta : {0.0, 0.5, 1.2, kPi / 2}) { // the view's angle to the axis
    const Vec3d d(std::sin(theta), std::cos(theta), 0);
    // 2 r h sin(theta) + pi r^2 |cos(theta)|: the side's rectangle and a cap's ellipse
    const double expected = 2 * r * h * std::sin(theta) + kPi * r * r * std::abs(std::cos(theta));
    const Silhouette got = silhouette(*s.geometry, d, 1.0, 2 * (h + 2 * r) + 2 * kPi * r);
    EXPECT_NEAR(got.area, expected, got.tolerance) << "theta " << theta;
    const Silhouette flat = silhouette(*disk.geometry, d, 1.0, 2 * kPi * r);
    EXPECT_NEAR(flat.area, kPi * r * r * std::abs(std::cos(theta)), flat.tolerance + 1e-12);
  }
  // An open tube seen along its axis: nothing but its wall's edge.
  const RenderScene open =
      sceneOf("<cylinder><p0>0,-0.75,0</p0><p1>0,0.75,0</p1><radius>0.4"
              "</radius><material>matte</material><reflectance>0.5</reflectance></cylinder>");
  const Silhouette along = silhouette(*open.geometry, Vec3d(0, 1, 0), 1.0, 2 * kPi * r);
  EXPECT_LT(along.area, along.tolerance);
}

// Hits lie on the surface to float precision, from outside and from inside (the far wall).
TEST(AnalyticShapes, CylinderHitsLieOnTheTubeAndTheCaps) {
  const CylinderShape c{Vec3d(1, 2, 3), Vec3d(2, 4, 3.5), 0.7, true};
  const RenderScene s =
      sceneOf("<cylinder><p0>1,2,3</p0><p1>2,4,3.5</p1><radius>0.7</radius><capped>true</capped>"
              "<material>matte</material><reflectance>0.5</reflectance></cylinder>");
  const Vec3d mid = (c.p0 + c.p1) * 0.5, a = c.axis();
  int side = 0, caps = 0;
  for (uint32_t i = 0; i < 4000; ++i) {
    const Sample2 u = uniform2(i), v = uniform2(i + 100000);
    const bool inside = i % 2;
    const Vec3d o = inside ? mid + Vec3d(sampleUniformSphere(u)) * 0.3
                           : mid + Vec3d(sampleUniformSphere(u)) * 5.0;
    const Vec3d target = mid + Vec3d(sampleUniformSphere(v)) * 1.2;
    Ray r;
    r.o = Vec3(o);
    r.d = Vec3(normalize(target - o));
    SurfaceHit h;
    if (!s.geometry->intersect(r, h)) {
      EXPECT_FALSE(inside) << "a ray from inside a closed cylinder leaves it";
      continue;
    }
    ASSERT_EQ(h.kind, ShapeKind::Cylinder);
    const Vec3d q = Vec3d(h.p) - c.p0;
    const double z = dot(q, a), radial = length(q - a * z);
    const double tol = 4e-6 * (1 + length(Vec3d(h.p)));
    if (static_cast<CylinderPart>(h.prim) == CylinderPart::Side) {
      ++side;
      EXPECT_NEAR(radial, 0.7, tol);
      EXPECT_GE(z, -tol);
      EXPECT_LE(z, c.height() + tol);
      EXPECT_NEAR(dot(Vec3d(h.ng), a), 0, 1e-6);
    } else {
      ++caps;
      EXPECT_LE(radial, 0.7 + tol);
      EXPECT_NEAR(z, static_cast<CylinderPart>(h.prim) == CylinderPart::Top ? c.height() : 0.0,
                  tol);
    }
    // the reference: the same hit from the kind's own function in double
    const auto ref = intersectCylinder(c, Vec3d(r.o), Vec3d(r.d), 0, INFINITY);
    ASSERT_TRUE(ref);
    EXPECT_NEAR(h.t, ref->t, 1e-5 * (1 + ref->t));
  }
  EXPECT_GT(side, 500);
  EXPECT_GT(caps, 100);
}

const std::string kDiskLight =
    "<disk><center>0,1,0</center><normal>0,-1,0</normal><radius>0.8</radius>"
    "<material>matte</material><emission>2</emission></disk>";

using test::pdfTowards;

// E = pi L r^2 / (r^2 + h^2) on the axis of a Lambertian disk of radiance L, facing it.
TEST(AnalyticShapes, DiskLightIrradianceOnItsAxis) {
  const RenderScene s = sceneOf(kDiskLight);
  const LightSampler lights(s);
  for (const double h : {0.25, 1.0, 3.0}) {
    const Vec3 p(0, static_cast<float>(1 - h), 0), n(0, 1, 0);
    test::RunningStats e;
    for (uint32_t i = 0; i < 40000; ++i) {
      LightSample ls;
      ASSERT_TRUE(lights.sample(p, 0.5f, uniform2(i), test::flatWavelengths(500), ls, n));
      EXPECT_NEAR(ls.pdf, pdfTowards(s, lights, p, ls.wi), 2e-3f * ls.pdf);
      e.add(ls.radiance[0] * std::max(0.0f, dot(ls.wi, n)) / ls.pdf);
    }
    const double expected = kPi * 2 * 0.64 / (0.64 + h * h);
    EXPECT_NEAR(e.mean, expected, 5 * e.standardError() + 1e-9) << "h " << h;
    EXPECT_LT(e.standardError(), 0.02 * expected); // the test has power
  }
}

// Points of a disk light are uniform by area: chi-square over cells of equal area in
// (r^2 / R^2, phi); and the density of each direction is the pdf MIS uses for it.
TEST(AnalyticShapes, DiskLightSamplingIsUniformByArea) {
  const RenderScene s = sceneOf(kDiskLight);
  const LightSampler lights(s);
  const Vec3 p(0.2f, 0.6f, -0.1f); // close and off the axis: every part of the disk at its angle
  const int n = 200000, nr = 20, nphi = 20;
  std::vector<double> obs(nr * nphi, 0), exp(nr * nphi, n / double(nr * nphi));
  for (int i = 0; i < n; ++i) {
    LightSample ls;
    ASSERT_TRUE(
        lights.sample(p, 0.5f, uniform2(static_cast<uint32_t>(i)), test::flatWavelengths(500), ls));
    if (i < 2000) {
      EXPECT_NEAR(ls.pdf, pdfTowards(s, lights, p, ls.wi), 2e-3f * ls.pdf);
    }
    const Vec3 q = ls.p - Vec3(0, 1, 0);
    EXPECT_NEAR(q.y, 0, 1e-6f);
    const double r2 = (q.x * q.x + q.z * q.z) / 0.64;
    ASSERT_LE(r2, 1 + 1e-5);
    const double phi = std::atan2(q.z, q.x) + kPi;
    obs[std::min(nr - 1, static_cast<int>(r2 * nr)) * nphi +
        std::min(nphi - 1, static_cast<int>(phi / (2 * kPi) * nphi))] += 1;
  }
  const auto [stat, dof] = test::chiSquare(obs, exp);
  EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << "chi2 " << stat << " dof " << dof;
}

// Irradiance from a cylinder light (its side seen from outside, the caps) estimated by light
// sampling with shadow rays equals the estimate of cosine-weighted directions that find it:
// the sampling's density and the pdf for MIS agree, whatever part is sampled.
TEST(AnalyticShapes, CylinderLightSamplingAgreesWithDirectionsThatFindIt) {
  const RenderScene s = sceneOf(
      "<cylinder><p0>-0.5,1,0</p0><p1>0.5,1.4,0.3</p1><radius>0.3</radius><capped>true</capped>"
      "<material>matte</material><emission>1</emission></cylinder>");
  const LightSampler lights(s);
  const Vec3 p(0.1f, 0, 0), n(0, 1, 0);
  test::RunningStats byLight, byDirection;
  for (uint32_t i = 0; i < 800000; ++i) {
    LightSample ls;
    if (lights.sample(p, 0.5f, uniform2(i), test::flatWavelengths(500), ls, n)) {
      Ray shadow;
      shadow.o = p;
      shadow.d = ls.wi;
      shadow.tMax = ls.distance * (1 - 1e-4f);
      const bool seen = !s.geometry->occluded(shadow);
      byLight.add(seen ? ls.radiance[0] * std::max(0.0f, dot(ls.wi, n)) / ls.pdf : 0.0);
    } else {
      byLight.add(0);
    }
    Ray r;
    r.o = p;
    r.d = Frame::fromNormal(n).toWorld(sampleCosineHemisphere(uniform2(i + 1000000)));
    SurfaceHit h;
    byDirection.add(s.geometry->intersect(r, h) && h.kind == ShapeKind::Cylinder ? kPi : 0.0);
  }
  const double se = std::hypot(byLight.standardError(), byDirection.standardError());
  EXPECT_NEAR(byLight.mean, byDirection.mean, 5 * se);
  EXPECT_LT(se, 0.006 * byDirection.mean); // a 3% error in the density fails
}

// Inside a closed shape of reflectance 1/2 emitting 1/2, radiance is 1/2 / (1 - 1/2) = 1
// everywhere (the interior furnace), whatever the shape.
TEST(AnalyticShapes, FurnaceInsideClosedBoxAndCylinder) {
  for (const std::string& shape :
       {std::string("<box><center>0,0,0</center><size>2,3,1.5</size>"),
        std::string("<cylinder><p0>0,-1,0</p0><p1>0,1,0</p1><radius>1.2</radius>"
                    "<capped>true</capped>")}) {
    const std::string tag = shape.substr(1, shape.find('>') - 1);
    const RenderOutput out = renderText(sceneText(
        "<xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>64</depth><sampl>256"
        "</sampl>",
        "<position>0.1,0.2,0</position><look_at>1,0.3,0.5</look_at>",
        shape +
            "<material>matte</material><reflectance>0.5</reflectance><emission>0.5"
            "</emission></" +
            tag + ">"));
    expectBands(
        out.film, [](int) { return 1.0; }, 0.02, {}, tag);
  }
}

} // namespace
} // namespace nx
