#include "io/mesh_cache.h"

#include <algorithm>
#include <list>
#include <mutex>

#include "core/memory.h"
#include "core/sha256.h"

namespace nx {
namespace {

struct Entry {
  MeshKey key;
  std::shared_ptr<const TriangleMesh> mesh;
  double size() const { return static_cast<double>(mesh->bytes()); }
};

struct MeshCache {
  std::mutex lock;
  std::list<Entry> entries; ///< most recently used first
};

MeshCache& cache() {
  static MeshCache c;
  return c;
}

} // namespace

MeshKey meshKeyOf(const std::string& bytes, const std::string& extension) {
  return {extension, bytes.size(), sha256(bytes)};
}

std::shared_ptr<const TriangleMesh> cachedMesh(const MeshKey& key) {
  MeshCache& c = cache();
  const std::lock_guard<std::mutex> guard(c.lock);
  for (auto it = c.entries.begin(); it != c.entries.end(); ++it)
    if (it->key == key) {
      c.entries.splice(c.entries.begin(), c.entries, it);
      return c.entries.front().mesh;
    }
  return nullptr;
}

void cacheMesh(const MeshKey& key, std::shared_ptr<const TriangleMesh> mesh) {
  const double limit = std::min(kMeshCacheBytes, 0.25 * memoryBudget().bytes);
  Entry e{key, std::move(mesh)};
  if (e.size() > limit) return;
  MeshCache& c = cache();
  const std::lock_guard<std::mutex> guard(c.lock);
  c.entries.push_front(std::move(e));
  double total = 0;
  for (auto it = c.entries.begin(); it != c.entries.end();) {
    total += it->size();
    it = total > limit ? c.entries.erase(it) : std::next(it);
  }
}

void clearMeshCache() {
  MeshCache& c = cache();
  const std::lock_guard<std::mutex> guard(c.lock);
  c.entries.clear();
}

size_t cachedMeshCount() {
  MeshCache& c = cache();
  const std::lock_guard<std::mutex> guard(c.lock);
  return c.entries.size();
}

} // namespace nx
