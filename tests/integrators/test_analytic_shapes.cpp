// Boxes, disks, cylinders and capsules against closed forms: silhouettes (projected areas from
// a grid of parallel rays), exact hits on the surface (a capsule's against a root search on its
// distance function), uv, a disk light's irradiance on its axis and the chi-square of its
// sampling, cylinder and capsule lights sampled as BSDF sampling finds them, the furnace inside
// the closed ones, and Beer-Lambert through a capsule holding an absorber.

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

// Irradiance at p from the one emitter of `s` (of `kind`), by light sampling with shadow rays
// and by cosine-weighted directions that find it: equal within 5 standard errors, which are
// below 0.6% (a 3% error in the density fails); with `checkPdf`, the pdf MIS uses for each
// sampled direction away from the silhouette equals the sampling's own (at grazing angles
// float directions miss or meet it elsewhere, and d^2 / |cos| magnifies that rounding).
void expectLightSamplingAgreesWithDirections(const RenderScene& s, ShapeKind kind, bool checkPdf) {
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
      if (checkPdf && seen && i < 20000 && std::abs(dot(ls.n, ls.wi)) > 0.1f) {
        EXPECT_NEAR(ls.pdf, pdfTowards(s, lights, p, ls.wi), 2e-3f * ls.pdf);
      }
      byLight.add(seen ? ls.radiance[0] * std::max(0.0f, dot(ls.wi, n)) / ls.pdf : 0.0);
    } else {
      byLight.add(0);
    }
    Ray r;
    r.o = p;
    r.d = Frame::fromNormal(n).toWorld(sampleCosineHemisphere(uniform2(i + 1000000)));
    SurfaceHit h;
    byDirection.add(s.geometry->intersect(r, h) && h.kind == kind ? kPi : 0.0);
  }
  const double se = std::hypot(byLight.standardError(), byDirection.standardError());
  EXPECT_NEAR(byLight.mean, byDirection.mean, 5 * se);
  EXPECT_LT(se, 0.006 * byDirection.mean); // a 3% error in the density fails
}

// Irradiance from a cylinder light (its side seen from outside, the caps) estimated by light
// sampling with shadow rays equals the estimate of cosine-weighted directions that find it:
// the sampling's density and the pdf for MIS agree, whatever part is sampled.
TEST(AnalyticShapes, CylinderLightSamplingAgreesWithDirectionsThatFindIt) {
  expectLightSamplingAgreesWithDirections(
      sceneOf("<cylinder><p0>-0.5,1,0</p0><p1>0.5,1.4,0.3</p1><radius>0.3</radius><capped>true"
              "</capped><material>matte</material><emission>1</emission></cylinder>"),
      ShapeKind::Cylinder, false);
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

const std::string kCapsule = "<capsule><p0>0,-0.75,0</p0><p1>0,0.75,0</p1><radius>0.4</radius>"
                             "<material>matte</material><reflectance>0.5</reflectance></capsule>";

// A capsule seen at angle theta to its axis projects to a stadium: a rectangle of 2 r by
// h sin(theta) between two half disks, 2 r h sin(theta) + pi r^2.
TEST(AnalyticShapes, CapsuleSilhouetteIsAStadium) {
  const double r = 0.4, h = 1.5;
  const RenderScene s = sceneOf(kCapsule);
  for (const double theta : {0.0, 0.5, 1.2, kPi / 2}) {
    const Vec3d d(std::sin(theta), std::cos(theta), 0.3 * std::sin(theta));
    const double sinTheta = length(cross(normalize(d), Vec3d(0, 1, 0)));
    const Silhouette got = silhouette(*s.geometry, d, 1.3, 2 * h + 2 * kPi * r);
    EXPECT_NEAR(got.area, 2 * r * h * sinTheta + kPi * r * r, got.tolerance) << "theta " << theta;
  }
}

// The first root of the capsule's distance function dist(x, segment) - r along a ray, by
// steps of 1e-3 and bisection: an independent reference for its intersection.
double firstRootOfDistance(const CapsuleShape& c, const Vec3d& o, const Vec3d& d) {
  auto f = [&](double t) {
    const Vec3d x = o + d * t, a = c.axis();
    const double z = std::clamp(dot(x - c.p0, a), 0.0, c.height());
    return length(x - (c.p0 + a * z)) - c.radius;
  };
  const double start = f(1e-9);
  for (double t = 0; t < 20; t += 1e-3)
    if ((f(t + 1e-3) < 0) != (start < 0)) {
      double lo = t, hi = t + 1e-3;
      for (int i = 0; i < 60; ++i)
        ((f(0.5 * (lo + hi)) < 0) != (start < 0) ? hi : lo) = 0.5 * (lo + hi);
      return 0.5 * (lo + hi);
    }
  return INFINITY;
}

// Hits of rays from outside and from inside lie on the capsule (at distance r from its
// segment), on the part they name, with the outward normal, where a root search on its
// distance function finds them; a ray from inside always meets it. uv: u the angle around the
// axis, v the arc length from the pole beyond p0 over the meridian's h + pi r.
TEST(AnalyticShapes, CapsuleHitsLieOnItsSurfaceWhereItsDistanceFunctionVanishes) {
  const CapsuleShape c{Vec3d(1, 2, 3), Vec3d(2, 4, 3.5), 0.7};
  const RenderScene s = sceneOf("<capsule><p0>1,2,3</p0><p1>2,4,3.5</p1><radius>0.7</radius>"
                                "<material>matte</material><reflectance>0.5</reflectance>"
                                "</capsule>");
  const Vec3d mid = (c.p0 + c.p1) * 0.5, a = c.axis();
  const AxisFrame f = AxisFrame::of(a);
  const double meridian = c.height() + kPi * c.radius;
  int parts[3] = {0, 0, 0};
  for (uint32_t i = 0; i < 3000; ++i) {
    const Sample2 u = uniform2(i), v = uniform2(i + 100000);
    const bool inside = i % 2;
    const Vec3d o = inside ? mid + Vec3d(sampleUniformSphere(u)) * 0.3
                           : mid + Vec3d(sampleUniformSphere(u)) * 5.0;
    const Vec3d target = mid + Vec3d(sampleUniformSphere(v)) * 1.6;
    Ray r;
    r.o = Vec3(o);
    r.d = Vec3(normalize(target - o));
    const double reference = firstRootOfDistance(c, Vec3d(r.o), Vec3d(r.d));
    SurfaceHit h;
    if (!s.geometry->intersect(r, h)) {
      EXPECT_FALSE(inside) << "a ray from inside a capsule leaves it";
      EXPECT_FALSE(std::isfinite(reference)) << "a ray that meets the capsule misses it";
      continue;
    }
    ASSERT_EQ(h.kind, ShapeKind::Capsule);
    ASSERT_LT(h.prim, 3u);
    ++parts[h.prim];
    EXPECT_NEAR(h.t, reference, 2e-6 * (1 + reference));
    const Vec3d p(h.p), q = p - c.p0;
    const double z = dot(q, a);
    const Vec3d nearest = c.p0 + a * std::clamp(z, 0.0, c.height());
    const double tol = 4e-6 * (1 + length(p));
    EXPECT_NEAR(length(p - nearest), c.radius, tol);
    EXPECT_NEAR(length(Vec3d(h.ng) - normalize(p - nearest)), 0, 1e-5);
    const CapsulePart part = static_cast<CapsulePart>(h.prim);
    EXPECT_EQ(part, z < 0            ? CapsulePart::Base
                    : z > c.height() ? CapsulePart::Top
                                     : CapsulePart::Side)
        << "z " << z;
    // uv from the point, independently of fillHit
    const Vec3d across = q - a * z;
    double phi = std::atan2(dot(across, f.t), dot(across, f.s));
    if (phi < 0) phi += 2 * kPi;
    const double arc =
        part == CapsulePart::Side ? kPi / 2 * c.radius + z
        : part == CapsulePart::Base
            ? c.radius * std::acos(std::clamp(-z / c.radius, -1.0, 1.0))
            : meridian - c.radius * std::acos(std::clamp((z - c.height()) / c.radius, -1.0, 1.0));
    const double du = std::abs(h.u - phi / (2 * kPi));
    EXPECT_LT(std::min(du, 1 - du), 2e-5);
    EXPECT_NEAR(h.v, arc / meridian, 2e-5);
    // dp/du is the tangent of the circle around the axis: 2 pi times the distance from it
    EXPECT_NEAR(length(Vec3d(h.dpdu)), 2 * kPi * length(across), 1e-4);
  }
  EXPECT_GT(parts[0], 300);
  EXPECT_GT(parts[1], 100);
  EXPECT_GT(parts[2], 100);
}

// Irradiance from a capsule light (tube and ends) estimated by light sampling with shadow rays
// equals the estimate of cosine-weighted directions that find it; and the pdf MIS uses for
// each sampled direction is the sampling's own.
TEST(AnalyticShapes, CapsuleLightSamplingAgreesWithDirectionsThatFindIt) {
  expectLightSamplingAgreesWithDirections(
      sceneOf("<capsule><p0>-0.5,1,0</p0><p1>0.5,1.4,0.3</p1><radius>0.3</radius>"
              "<material>matte</material><emission>1</emission></capsule>"),
      ShapeKind::Capsule, true);
}

// The interior furnace inside a capsule (as inside the box and the cylinder above).
TEST(AnalyticShapes, FurnaceInsideCapsule) {
  const RenderOutput out = renderText(sceneText(
      "<xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><depth>64</depth><sampl>256</sampl>",
      "<position>0.1,0.2,0</position><look_at>1,0.3,0.5</look_at>",
      "<capsule><p0>0,-1,0</p0><p1>0,1,0</p1><radius>1.2</radius><material>matte</material>"
      "<reflectance>0.5</reflectance><emission>0.5</emission></capsule>"));
  expectBands(
      out.film, [](int) { return 1.0; }, 0.02, {}, "capsule");
}

// A test tube of absorbing liquid (an index-matched capsule holding a medium of sigma_a = 0.8)
// in a background of 1: along its axis the light crosses h + 2 r of it, across its middle 2 r,
// and from a camera inside it at the centre looking along the axis, h / 2 + r.
TEST(AnalyticShapes, BeerLambertThroughACapsuleHoldingAnAbsorber) {
  const double h = 1.5, r = 0.4, sigma = 0.8;
  const std::string tube = "<capsule><p0>0,0,-0.75</p0><p1>0,0,0.75</p1><radius>0.4</radius>"
                           "<material>interface</material><medium><sigma_a>0.8</sigma_a>"
                           "<sigma_s>0</sigma_s></medium></capsule>";
  const std::string settings = "<xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode>"
                               "<sampl>256</sampl><background>1</background>";
  struct View {
    const char* camera;
    double length;
  };
  for (const View& v :
       {View{"<position>0,0,-100</position><look_at>0,0,0</look_at><fov>0.02</fov>", h + 2 * r},
        View{"<position>-100,0,0</position><look_at>0,0,0</look_at><fov>0.02</fov>", 2 * r},
        View{"<position>0,0,0</position><look_at>0,0,1</look_at><fov>0.02</fov>", h / 2 + r}}) {
    const RenderOutput out = renderText(sceneText(settings, v.camera, tube));
    expectBands(
        out.film, [&](int) { return std::exp(-sigma * v.length); }, 0.01, {}, v.camera);
  }
}

} // namespace
} // namespace nx
