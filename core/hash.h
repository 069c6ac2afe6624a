#pragma once
// Stateless integer hashing: the root of every random number nxrender draws.

#include <cstdint>

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

} // namespace nx
