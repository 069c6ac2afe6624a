#include "core/memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "core/error.h"

namespace nx {
namespace {

// Virtual size and data size of this process in bytes (/proc/self/statm), or 0 if unknown.
void currentUse(double& virtualBytes, double& dataBytes) {
  virtualBytes = dataBytes = 0;
  std::ifstream statm("/proc/self/statm");
  double size = 0, resident = 0, shared = 0, text = 0, lib = 0, data = 0;
  if (statm >> size >> resident >> shared >> text >> lib >> data) {
    const double page = static_cast<double>(sysconf(_SC_PAGE_SIZE));
    virtualBytes = size * page;
    dataBytes = data * page;
  }
}

std::string gib(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  return buf;
}

} // namespace

MemoryBudget memoryBudget() {
  MemoryBudget b;
  const double physical =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  b.bytes = 0.8 * physical;
  b.limit = "80% of the machine's " + gib(physical);
  double virtualBytes = 0, dataBytes = 0;
  currentUse(virtualBytes, dataBytes);
  struct rlimit r {};
  if (getrlimit(RLIMIT_AS, &r) == 0 && r.rlim_cur != RLIM_INFINITY) {
    const double left = static_cast<double>(r.rlim_cur) - virtualBytes;
    if (left < b.bytes) {
      b.bytes = left > 0 ? left : 0;
      b.limit = "the process's address-space limit (ulimit -v) of " +
                gib(static_cast<double>(r.rlim_cur)) + ", " + gib(virtualBytes) + " of it in use";
    }
  }
  if (getrlimit(RLIMIT_DATA, &r) == 0 && r.rlim_cur != RLIM_INFINITY) {
    const double left = static_cast<double>(r.rlim_cur) - dataBytes;
    if (left < b.bytes) {
      b.bytes = left > 0 ? left : 0;
      b.limit = "the process's data limit (ulimit -d) of " + gib(static_cast<double>(r.rlim_cur)) +
                ", " + gib(dataBytes) + " of it in use";
    }
  }
  return b;
}

void requireMemory(double bytes, const std::string& where, const std::string& what,
                   const std::string& found) {
  const MemoryBudget b = memoryBudget();
  if (bytes <= b.bytes) return;
  throw Error(where + ": expected " + what + " whose buffers fit in memory, found " + found +
              " (needs " + gib(bytes) + "; " + gib(b.bytes) + " usable: " + b.limit + ")");
}

} // namespace nx
