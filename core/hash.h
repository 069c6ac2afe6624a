#pragma once
// Stateless integer hashing: the root of every random number nxrender draws.

#include <cstdint>
#include <string_view>

namespace nx {

/// A 32-bit integer mixer with low bias (C. Wellons, "lowbias32", 2018): every input bit
/// affects every output bit with probability close to 1/2.
constexpr uint32_t mix32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

/// Hash of four words; different argument orders give unrelated results.
constexpr uint32_t hash4(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  uint32_t h = mix32(d + 0x9e3779b9U);
  h = mix32(h ^ c);
  h = mix32(h + b);
  return mix32(h ^ a);
}

/// 64-bit FNV-1a hash of bytes, continuing from h (content digests: render keys, not random
/// numbers).
inline uint64_t fnv1a64(std::string_view data, uint64_t h = 0xcbf29ce484222325ULL) {
  for (unsigned char c : data) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

} // namespace nx
