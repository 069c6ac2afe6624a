#include "core/sampler.h"

#include "core/hash.h"
#include "core/math_util.h"

namespace nx {
namespace {

uint32_t reverseBits(uint32_t x) {
  x = ((x >> 1) & 0x55555555U) | ((x & 0x55555555U) << 1);
  x = ((x >> 2) & 0x33333333U) | ((x & 0x33333333U) << 2);
  x = ((x >> 4) & 0x0F0F0F0FU) | ((x & 0x0F0F0F0FU) << 4);
  x = ((x >> 8) & 0x00FF00FFU) | ((x & 0x00FF00FFU) << 8);
  return (x >> 16) | (x << 16);
}

// Burley 2020, section 3: a hash that, like an Owen scramble read from the least significant
// bit, only lets bits influence more significant bits.
uint32_t laineKarrasPermutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cU;
  x ^= x * 0xb82f1e52U;
  x ^= x * 0xc7afe638U;
  x ^= x * 0x8d22f6e6U;
  return x;
}

// Owen scrambling of a 0.32 fixed-point value: flips are nested from the most significant bit.
uint32_t nestedUniformScramble(uint32_t x, uint32_t seed) {
  return reverseBits(laineKarrasPermutation(reverseBits(x), seed));
}

// Sobol dimension 1 (primitive polynomial x + 1): v_0 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1).
uint32_t sobolDimension1(uint32_t index) {
  uint32_t result = 0;
  uint32_t v = 1U << 31;
  for (; index != 0; index >>= 1, v ^= v >> 1) {
    if (index & 1U) result ^= v;
  }
  return result;
}

constexpr uint32_t kShuffleSalt = 0x5f356495U;
constexpr uint32_t kScrambleSalt = 0x2c1b3c6dU;

} // namespace

Sample2 samplePair(SamplerKind kind, uint32_t pixel, uint32_t index, uint32_t pair, uint32_t seed) {
  if (kind == SamplerKind::Independent) {
    return {bitsToUnitFloat(hash4(pixel, index, 2 * pair, seed)),
            bitsToUnitFloat(hash4(pixel, index, 2 * pair + 1, seed))};
  }
  const uint32_t shuffled = nestedUniformScramble(index, hash4(pixel, pair, seed, kShuffleSalt));
  const uint32_t x = reverseBits(shuffled);
  const uint32_t y = sobolDimension1(shuffled);
  return {
      bitsToUnitFloat(nestedUniformScramble(x, hash4(pixel, 2 * pair, seed, kScrambleSalt))),
      bitsToUnitFloat(nestedUniformScramble(y, hash4(pixel, 2 * pair + 1, seed, kScrambleSalt)))};
}

float sampleValue(SamplerKind kind, uint32_t pixel, uint32_t index, uint32_t dim, uint32_t seed) {
  const Sample2 s = samplePair(kind, pixel, index, dim / 2, seed);
  return (dim & 1U) ? s.v : s.u;
}

} // namespace nx
