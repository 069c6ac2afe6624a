#include <gtest/gtest.h>

#include <cmath>

#include "accel/geometry_scene.h"
#include "core/camera.h"
#include "core/hash.h"
#include "core/math_util.h"
#include "core/ray_offset.h"

namespace nx {
namespace {

float rnd(uint32_t a, uint32_t b) {
  return bitsToUnitFloat(hash4(a, b, 0x51ab, 0));
}

Vec3 randomDirection(uint32_t a) {
  const float z = 1 - 2 * rnd(a, 1), phi = 2 * static_cast<float>(kPi) * rnd(a, 2);
  const float r = std::sqrt(std::max(0.0f, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

struct BruteForceHit {
  double t = INFINITY;
  ShapeKind kind = ShapeKind::Sphere;
  uint32_t index = 0;
};

BruteForceHit bruteForce(const GeometryScene& g, const Ray& r) {
  BruteForceHit best;
  const Vec3d o(r.o), d(r.d);
  auto consider = [&](std::optional<double> t, ShapeKind k, size_t i) {
    if (t && *t < best.t) best = {*t, k, static_cast<uint32_t>(i)};
  };
  for (size_t i = 0; i < g.spheres().size(); ++i)
    consider(intersectSphere(g.spheres()[i], o, d, r.tMin, r.tMax), ShapeKind::Sphere, i);
  for (size_t i = 0; i < g.planes().size(); ++i)
    consider(intersectPlane(g.planes()[i], o, d, r.tMin, r.tMax), ShapeKind::Plane, i);
  for (const TriangleMesh& m : g.meshes())
    for (size_t i = 0; i < m.triangleCount(); ++i)
      consider(intersectTriangle(m.corners(i), o, d, r.tMin, r.tMax), ShapeKind::Triangle, i);
  return best;
}

// Random rays against random scenes: the nearest hit (shape and distance) agrees with an
// independent brute-force intersection of every primitive, and occlusion agrees with it.
TEST(GeometryScene, AgreesWithBruteForceOnRandomScenes) {
  EmbreeDevice device;
  int cases = 0, hits = 0;
  for (uint32_t sceneId = 0; sceneId < 20; ++sceneId) {
    std::vector<SphereShape> spheres;
    std::vector<PlaneShape> planes;
    std::vector<TriangleShape> tris;
    const int nSpheres = 1 + static_cast<int>(rnd(sceneId, 100) * 40);
    for (int i = 0; i < nSpheres; ++i) {
      const uint32_t k = sceneId * 1000 + static_cast<uint32_t>(i);
      spheres.push_back({Vec3d(20 * rnd(k, 3) - 10, 20 * rnd(k, 4) - 10, 20 * rnd(k, 5) - 10),
                         0.1 + 3 * rnd(k, 6)});
    }
    for (int i = 0; i < 2; ++i) {
      const uint32_t k = sceneId * 1000 + 500 + static_cast<uint32_t>(i);
      planes.push_back({Vec3d(randomDirection(k)), 15 + 5 * rnd(k, 7)});
    }
    for (int i = 0; i < 10; ++i) {
      const uint32_t k = sceneId * 1000 + 700 + static_cast<uint32_t>(i);
      const Vec3d c(20 * rnd(k, 8) - 10, 20 * rnd(k, 9) - 10, 20 * rnd(k, 10) - 10);
      tris.push_back(
          {c, c + Vec3d(randomDirection(k + 1)) * 3.0, c + Vec3d(randomDirection(k + 2)) * 3.0});
    }
    GeometryScene g(device, spheres, planes, {TriangleMesh::fromTriangles(tris)});
    for (uint32_t r = 0; r < 500; ++r) {
      const uint32_t k = sceneId * 100000 + r;
      Ray ray;
      ray.o = Vec3(24 * rnd(k, 11) - 12, 24 * rnd(k, 12) - 12, 24 * rnd(k, 13) - 12);
      ray.d = randomDirection(k);
      const BruteForceHit ref = bruteForce(g, ray);
      SurfaceHit hit;
      const bool found = g.intersect(ray, hit);
      ++cases;
      ASSERT_EQ(found, std::isfinite(ref.t)) << "scene " << sceneId << " ray " << r;
      EXPECT_EQ(g.occluded(ray), found);
      if (!found) continue;
      ++hits;
      EXPECT_NEAR(hit.t, ref.t, 1e-4 * std::max(1.0, ref.t));
      if (std::abs(hit.t - ref.t) > 1e-3) continue; // a near tie between two shapes
      EXPECT_EQ(hit.kind, ref.kind);
      EXPECT_EQ(hit.kind == ShapeKind::Triangle ? hit.prim : hit.index, ref.index);
      EXPECT_NEAR(length(hit.ng), 1.0f, 1e-5f);
    }
  }
  EXPECT_EQ(cases, 10000);
  EXPECT_GT(hits, 5000); // most rays hit something (the planes close the scene partly)
}

TEST(GeometryScene, RayStartingInsideSphereHitsFarSide) {
  EmbreeDevice device;
  GeometryScene g(device, {{Vec3d(1, 2, 3), 2.0}}, {}, {});
  for (uint32_t i = 0; i < 100; ++i) {
    Ray r;
    r.o = Vec3(1, 2, 3);
    r.d = randomDirection(i);
    SurfaceHit h;
    ASSERT_TRUE(g.intersect(r, h));
    EXPECT_NEAR(h.t, 2.0f, 1e-5f);
    EXPECT_GT(dot(h.ng, r.d), 0.99f); // outward normal, same side as the ray
  }
}

TEST(GeometryScene, TangentAndGrazingRaysGiveNoNaN) {
  EmbreeDevice device;
  GeometryScene g(device, {{Vec3d(0, 0, 0), 1.0}}, {}, {});
  for (int i = -50; i <= 50; ++i) {
    Ray r;
    r.o = Vec3(-5, 1.0f + static_cast<float>(i) * 1e-7f, 0);
    r.d = Vec3(1, 0, 0);
    SurfaceHit h;
    if (g.intersect(r, h)) {
      EXPECT_TRUE(isFinite(h.p));
      EXPECT_NEAR(length(h.p), 1.0f, 1e-5f);
    }
  }
  EXPECT_EQ(g.nonFiniteHits(), 0u);
}

// Secondary rays leave surfaces without re-hitting them (no acne) and without tunnelling
// through them, for a tiny sphere, a unit sphere and a huge sphere alike: hit the sphere from
// outside, then leave the hit point outwards (reflection) or inwards (refraction).
TEST(GeometryScene, OffsetOriginsAvoidSelfIntersectionAtEveryScale) {
  EmbreeDevice device;
  for (double radius : {1e-5, 1.0, 1e5}) {
    const Vec3d centre(0.3 * radius, -radius, 2 * radius);
    GeometryScene g(device, {{centre, radius}}, {}, {});
    int primaryHits = 0, reflectedHits = 0, refractedMisses = 0;
    for (uint32_t i = 0; i < 4000; ++i) {
      Ray primary;
      primary.o = Vec3(centre + Vec3d(randomDirection(i)) * (3 * radius));
      const Vec3 target = Vec3(centre + Vec3d(randomDirection(i + 99999)) * (0.9 * radius));
      primary.d = normalize(target - primary.o);
      SurfaceHit hit;
      if (!g.intersect(primary, hit)) continue;
      ++primaryHits;
      Vec3 d = randomDirection(i + 7777);
      if (dot(d, hit.ng) < 0) d = -d;
      Ray out;
      out.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, d);
      out.d = d;
      SurfaceHit h;
      reflectedHits += g.intersect(out, h);
      Ray in;
      in.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, -d);
      in.d = -d;
      // The far side lies at the chord length 2 r cos(theta), not at the entry point (for
      // grazing directions the offset origin lengthens the exit distance slightly).
      const double chord = 2 * radius * std::abs(dot(d, hit.ng));
      if (!g.intersect(in, h) || h.t < 0.5 * chord || h.t > chord + 2e-3 * radius)
        ++refractedMisses;
    }
    EXPECT_EQ(primaryHits, 4000) << "radius " << radius;
    EXPECT_EQ(reflectedHits, 0) << "radius " << radius;
    EXPECT_EQ(refractedMisses, 0) << "radius " << radius;
  }
}

// A light 1e5 away seen from a 1e-5 sphere: the lit side is unoccluded, the far side is
// shadowed by the sphere itself.
TEST(GeometryScene, TinySphereAndFarLight) {
  EmbreeDevice device;
  GeometryScene g(device, {{Vec3d(0, 0, 0), 1e-5}}, {}, {});
  const Vec3 light(0, 1e5f, 0);
  for (const Vec3 n : {Vec3(0, 1, 0), normalize(Vec3(0.3f, 1, 0)), Vec3(0, -1, 0)}) {
    const Vec3 p = n * 1e-5f;
    Ray shadow;
    shadow.o = offsetRayOrigin(p, roundingError(p), n, n);
    const Vec3 toLight = light - shadow.o;
    shadow.d = normalize(toLight);
    shadow.tMax = length(toLight) * (1 - 1e-6f);
    EXPECT_EQ(g.occluded(shadow), n.y < 0) << n.y;
  }
}

// A floor made of a sphere of radius 1e5 is hit where a plane floor is hit, at the same
// points with the same normals, over the camera's view.
TEST(GeometryScene, HugeSphereFloorMatchesPlaneFloor) {
  EmbreeDevice device;
  GeometryScene sphereFloor(device, {{Vec3d(0, -1e5, 0), 1e5}}, {}, {});
  GeometryScene planeFloor(device, std::vector<SphereShape>{}, {{Vec3d(0, 1, 0), 0}}, {});
  const PinholeCamera cam(Vec3d(0, 2, -5), Vec3d(0, 0, 5), Vec3d(0, 1, 0), 60, 64, 48);
  int compared = 0;
  for (int y = 24; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const Ray r = cam.generateRay(x + 0.5, y + 0.5);
      SurfaceHit a, b;
      const bool ha = sphereFloor.intersect(r, a), hb = planeFloor.intersect(r, b);
      ASSERT_EQ(ha, hb);
      if (!ha || b.t > 50) continue; // far away the sphere's curvature shows
      ++compared;
      EXPECT_NEAR(a.t, b.t, 2e-3f * b.t);
      EXPECT_NEAR(a.ng.y, 1.0f, 1e-6f);
      EXPECT_NEAR(a.p.y, 0.0f, 1e-2f);
    }
  EXPECT_GT(compared, 500);
}

// A camera 1 mm above an infinite plane looking at the horizon: every pixel row below the
// horizon sees the plane, however far away the hit is.
TEST(GeometryScene, PlaneReachesTheHorizon) {
  EmbreeDevice device;
  GeometryScene g(device, std::vector<SphereShape>{}, {{Vec3d(0, 1, 0), 0}}, {});
  const int h = 1001;
  const PinholeCamera cam(Vec3d(0, 1e-3, 0), Vec3d(0, 1e-3, 1), Vec3d(0, 1, 0), 60, h, h);
  for (int y = 0; y < h; ++y) {
    const Ray r = cam.generateRay(500.5, y + 0.5);
    SurfaceHit hit;
    const bool below = r.d.y < 0;
    EXPECT_EQ(g.intersect(r, hit), below) << "row " << y;
    if (below) {
      EXPECT_NEAR(hit.p.y, 0.0f, 1e-6f);
      EXPECT_TRUE(std::isfinite(hit.t));
    }
  }
  // The row just below the centre meets the plane very far away.
  SurfaceHit far;
  ASSERT_TRUE(g.intersect(cam.generateRay(500.5, 500.9), far));
  EXPECT_GT(far.t, 1.0f);
}

TEST(GeometryScene, EmptyScene) {
  EmbreeDevice device;
  GeometryScene g(device, std::vector<SphereShape>{}, {}, {});
  Ray r;
  r.d = Vec3(0, 0, 1);
  SurfaceHit h;
  EXPECT_FALSE(g.intersect(r, h));
  EXPECT_FALSE(g.occluded(r));
}

TEST(Camera, NiixtracerConventionAndAnyDirection) {
  const PinholeCamera c(Vec3d(0, 0, 0), Vec3d(0, 0, 1), Vec3d(0, 1, 0), 90, 200, 100);
  const Ray centre = c.generateRay(100, 50), rightEdge = c.generateRay(200, 50),
            top = c.generateRay(100, 0);
  EXPECT_NEAR(centre.d.z, 1.0f, 1e-6f);
  EXPECT_GT(rightEdge.d.x, 0.0f);                   // +x on the right
  EXPECT_NEAR(rightEdge.d.x, rightEdge.d.z, 1e-6f); // 90 degrees horizontal field of view
  EXPECT_GT(top.d.y, 0.0f);                         // +y up
  EXPECT_NEAR(top.d.y / top.d.z, 0.5f, 1e-6f);      // vertical extent from the aspect ratio
  // Looking along -z: not upside down (+y still up), +x now on the left.
  const PinholeCamera back(Vec3d(0, 0, 0), Vec3d(0, 0, -1), Vec3d(0, 1, 0), 90, 200, 100);
  EXPECT_GT(back.generateRay(100, 0).d.y, 0.0f);
  EXPECT_LT(back.generateRay(200, 50).d.x, 0.0f);
  // Straight down and straight up: a valid orthonormal frame.
  for (const Vec3d target : {Vec3d(0, -1, 0), Vec3d(0, 1, 0)}) {
    const PinholeCamera v(Vec3d(0, 0, 0), target, Vec3d(0, 1, 0), 60, 10, 10);
    EXPECT_NEAR(length(v.right()), 1.0, 1e-12);
    EXPECT_NEAR(dot(v.right(), v.up()), 0.0, 1e-12);
    EXPECT_NEAR(dot(v.forward(), v.up()), 0.0, 1e-12);
    const Ray r = v.generateRay(5, 5);
    EXPECT_NEAR(r.d.y, static_cast<float>(target.y), 1e-6f);
  }
}

} // namespace
} // namespace nx
