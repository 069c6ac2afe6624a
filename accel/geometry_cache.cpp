#include "accel/geometry_cache.h"

#include <atomic>
#include <mutex>

#include "accel/embree_device.h"
#include "core/memory.h"

namespace nx {
namespace {

// An Embree device and the geometry built on it: one owner, so that the geometry never
// outlives its device.
struct BuiltGeometry {
  std::unique_ptr<EmbreeDevice> device;
  std::unique_ptr<GeometryScene> scene;
};

struct GeometryCache {
  std::mutex lock;
  std::shared_ptr<const BuiltGeometry> kept;
  std::atomic<size_t> built{0};
};

GeometryCache& cache() {
  static GeometryCache c;
  return c;
}

bool sameShapes(const GeometryScene& g, const AnalyticShapes& analytic,
                const std::vector<PlaneShape>& planes, const std::vector<TriangleMesh>& meshes) {
  // Each shape type's == is defaulted: a field added later is compared without a change here.
  return g.analytic() == analytic && g.planes() == planes && g.meshes() == meshes;
}

std::shared_ptr<const GeometryScene> sceneOf(const std::shared_ptr<const BuiltGeometry>& b) {
  return {b, b->scene.get()}; // shares b's ownership: the device lives as long
}

} // namespace

std::shared_ptr<const GeometryScene> sharedGeometry(std::vector<SphereShape> spheres,
                                                    std::vector<PlaneShape> planes,
                                                    std::vector<TriangleMesh> meshes) {
  AnalyticShapes analytic;
  std::get<std::vector<SphereShape>>(analytic) = std::move(spheres);
  return sharedGeometry(std::move(analytic), std::move(planes), std::move(meshes));
}

std::shared_ptr<const GeometryScene> sharedGeometry(AnalyticShapes analytic,
                                                    std::vector<PlaneShape> planes,
                                                    std::vector<TriangleMesh> meshes) {
  GeometryCache& c = cache();
  std::unique_lock<std::mutex> guard(c.lock);
  if (c.kept && sameShapes(*c.kept->scene, analytic, planes, meshes)) return sceneOf(c.kept);
  c.kept.reset(); // freed before the build (if no render still holds it)
  guard.unlock(); // builds run in parallel
  auto b = std::make_shared<BuiltGeometry>();
  b->device = std::make_unique<EmbreeDevice>();
  b->scene = std::make_unique<GeometryScene>(*b->device, std::move(analytic), std::move(planes),
                                             std::move(meshes));
  c.built.fetch_add(1, std::memory_order_relaxed);
  size_t bytes = b->scene->embreeBytes();
  for (const TriangleMesh& m : b->scene->meshes()) bytes += m.bytes();
  if (static_cast<double>(bytes) <= 0.25 * memoryBudget().bytes) {
    guard.lock();
    c.kept = b;
  }
  return sceneOf(b);
}

void clearGeometryCache() {
  GeometryCache& c = cache();
  const std::lock_guard<std::mutex> guard(c.lock);
  c.kept.reset();
}

size_t geometriesBuilt() {
  return cache().built.load(std::memory_order_relaxed);
}

} // namespace nx
