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

// Sobol dimension 1 (primitive polynomial x + 1): v_0 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1);
// the value of an index is the XOR of v_k over its set bits k. Tabulated per index byte, so a
// value costs four lookups instead of a loop over 32 bits.
struct SobolDimension1Table {
  uint32_t byByte[4][256];
  SobolDimension1Table() {
    uint32_t v[32];
    v[0] = 1U << 31;
    for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
    for (int byte = 0; byte < 4; ++byte)
      for (uint32_t value = 0; value < 256; ++value) {
        uint32_t x = 0;
        for (int bit = 0; bit < 8; ++bit)
          if (value & (1U << bit)) x ^= v[8 * byte + bit];
        byByte[byte][value] = x;
      }
  }
};
const SobolDimension1Table kSobol1;

uint32_t sobolDimension1(uint32_t index) {
  return kSobol1.byByte[0][index & 0xffU] ^ kSobol1.byByte[1][(index >> 8) & 0xffU] ^
         kSobol1.byByte[2][(index >> 16) & 0xffU] ^ kSobol1.byByte[3][index >> 24];
}

constexpr uint32_t kShuffleSalt = 0x5f356495U;
constexpr uint32_t kScrambleSalt = 0x2c1b3c6dU;

} // namespace

Sample2 samplePair(SamplerKind kind, uint32_t pixel, uint32_t index, uint32_t pair, uint32_t seed) {
  if (kind == SamplerKind::Independent || pair >= kSobolPairs) {
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
