// The geometry last built is shared by the next build of exactly the same shapes; any change
// (a radius, one coordinate of one mesh vertex, a plane) builds anew, and a geometry still held
// by a render stays valid after the cache moved on.

#include <gtest/gtest.h>

#include "accel/geometry_cache.h"
#include "core/ray.h"

namespace nx {
namespace {

TriangleMesh square(float corner) {
  return TriangleMesh::fromTriangles(
      {{{corner, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{corner, 0, 0}, {1, 1, 0}, {0, 1, 0}}});
}

float hitDistance(const GeometryScene& g, const Vec3& from) {
  Ray r;
  r.o = from;
  r.d = Vec3(0, 0, 1);
  SurfaceHit hit;
  return g.intersect(r, hit) ? hit.t : -1.0f;
}

TEST(GeometryCache, EqualShapesShareOneBuildAndAnyChangeBuildsAnew) {
  const std::vector<SphereShape> spheres{{{0, 0, 5}, 1}};
  const std::vector<PlaneShape> planes{{{0, 1, 0}, -3}};
  const size_t before = geometriesBuilt();
  const auto first = sharedGeometry(spheres, planes, {square(0)});
  const auto again = sharedGeometry(spheres, planes, {square(0)});
  EXPECT_EQ(first.get(), again.get());
  EXPECT_EQ(geometriesBuilt(), before + 1);

  // A different radius, one mesh coordinate, a plane's distance: each a new build.
  const auto radius = sharedGeometry({{{0, 0, 5}, 2}}, planes, {square(0)});
  EXPECT_NE(radius.get(), first.get());
  EXPECT_EQ(geometriesBuilt(), before + 2);
  const auto vertex = sharedGeometry({{{0, 0, 5}, 2}}, planes, {square(0.001f)});
  EXPECT_NE(vertex.get(), radius.get());
  const auto plane = sharedGeometry({{{0, 0, 5}, 2}}, {{{0, 1, 0}, -4}}, {square(0.001f)});
  EXPECT_NE(plane.get(), vertex.get());
  EXPECT_EQ(geometriesBuilt(), before + 4);

  // The first geometry, held all along, still answers its own rays: the sphere of radius 1.
  EXPECT_NEAR(hitDistance(*first, Vec3(0, 0, 0)), 4.0f, 1e-5f);
  EXPECT_NEAR(hitDistance(*radius, Vec3(0, 0, 0)), 3.0f, 1e-5f);
  // Only the last is kept: the first's shapes build again.
  const auto back = sharedGeometry(spheres, planes, {square(0)});
  EXPECT_EQ(geometriesBuilt(), before + 5);
  EXPECT_NEAR(hitDistance(*back, Vec3(0, 0, 0)), 4.0f, 1e-5f);
}

} // namespace
} // namespace nx
