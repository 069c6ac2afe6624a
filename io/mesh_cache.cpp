#include "io/mesh_cache.h"

#include <algorithm>
#include <functional>
#include <list>
#include <mutex>
#include <string_view>

#include "core/memory.h"

namespace nx {
namespace {

struct Entry {
  std::string extension;
  size_t hash;
  std::string bytes;
  std::shared_ptr<const TriangleMesh> mesh;
  double size() const { return static_cast<double>(bytes.size() + mesh->bytes()); }
};

struct MeshCache {
  std::mutex lock;
  std::list<Entry> entries; ///< most recently used first
};

MeshCache& cache() {
  static MeshCache c;
  return c;
}

size_t hashOf(const std::string& bytes) {
  return std::hash<std::string_view>{}(std::string_view(bytes));
}

} // namespace

std::shared_ptr<const TriangleMesh> cachedMesh(const std::string& bytes,
                                               const std::string& extension) {
  const size_t h = hashOf(bytes);
  MeshCache& c = cache();
  const std::lock_guard<std::mutex> guard(c.lock);
  for (auto it = c.entries.begin(); it != c.entries.end(); ++it)
    if (it->hash == h && it->extension == extension && it->bytes == bytes) {
      c.entries.splice(c.entries.begin(), c.entries, it);
      return c.entries.front().mesh;
    }
  return nullptr;
}

void cacheMesh(const std::string& bytes, const std::string& extension, const TriangleMesh& mesh) {
  const double limit = std::min(kMeshCacheBytes, 0.25 * memoryBudget().bytes);
  Entry e{extension, hashOf(bytes), bytes, std::make_shared<const TriangleMesh>(mesh)};
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

size_t cachedMeshCount() {
  MeshCache& c = cache();
  const std::lock_guard<std::mutex> guard(c.lock);
  return c.entries.size();
}

} // namespace nx
