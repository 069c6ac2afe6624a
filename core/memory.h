#pragma once
// How much memory this process may still use: what checks before rendering or merging compare
// their buffers with, so that a job too big is refused with figures instead of ending in
// std::bad_alloc.

#include <string>

namespace nx {

/// What the process can still allocate, in bytes, and what limits it.
struct MemoryBudget {
  double bytes = 0;  ///< the smallest of the limits below
  std::string limit; ///< which limit that is, for messages
};

/// 80% of the physical memory, or less if the process's address-space (RLIMIT_AS) or data
/// (RLIMIT_DATA) limit, minus what the process already uses, leaves less.
MemoryBudget memoryBudget();

/// Throws nx::Error "<where>: expected <what> whose buffers fit in memory, found <found>
/// (needs X GiB; Y GiB usable: <limit>)" when `bytes` exceed the budget.
void requireMemory(double bytes, const std::string& where, const std::string& what,
                   const std::string& found);

} // namespace nx
