#include "core/sampler.h"

#include "core/hash.h"
#include "core/math_util.h"

namespace nx {
namespace {

uint32_t reverseBits(uint32_t x) {
  x = ((x >> 1) & 0x55555555U) | ((x & 0x55555555U) << 1);
  x = ((x >> 2) & 0x33333333U) | ((x & 0x33333333U) << 2);
  x = ((x >> 4) & 0x0F0F0F0FU) | ((x & 0x0F0F0F0FU) << 4);
  return __builtin_bswap32(x); // reverses the byte order: the last two swap steps at once
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

// Owen scrambling of a 0.32 fixed-point value given bit-reversed: flips are nested from the
// most significant bit of the value, i.e. from the least significant bit of `reversed`.
uint32_t scrambleReversed(uint32_t reversed, uint32_t seed) {
  return reverseBits(laineKarrasPermutation(reversed, seed));
}

// A Sobol dimension tabulated per index byte from its direction numbers v_0..v_31 (the value
// of an index is the XOR of v_k over its set bits k): a value costs four lookups instead of a
// loop over 32 bits. The table holds the values bit-reversed (reversal commutes with XOR),
// which is the form the scrambling takes.
struct SobolDimensionTable {
  uint32_t byByte[4][256];
  explicit SobolDimensionTable(const uint32_t (&v)[32]) {
    for (int byte = 0; byte < 4; ++byte)
      for (uint32_t value = 0; value < 256; ++value) {
        uint32_t x = 0;
        for (int bit = 0; bit < 8; ++bit)
          if (value & (1U << bit)) x ^= v[8 * byte + bit];
        byByte[byte][value] = reverseBits(x);
      }
  }
  /// The dimension's value of an index, bit-reversed.
  uint32_t reversed(uint32_t index) const {
    return byByte[0][index & 0xffU] ^ byByte[1][(index >> 8) & 0xffU] ^
           byByte[2][(index >> 16) & 0xffU] ^ byByte[3][index >> 24];
  }
};

// Sobol dimension 1 (primitive polynomial x + 1): v_0 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1).
SobolDimensionTable sobolDimension1() {
  uint32_t v[32];
  v[0] = 1U << 31;
  for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
  return SobolDimensionTable(v);
}
const SobolDimensionTable kSobol1 = sobolDimension1();

// Sobol dimension 2 (primitive polynomial x^2 + x + 1, initial m = 1, 3: Joe and Kuo 2008,
// "Constructing Sobol sequences with better two-dimensional projections", dimension 3 of their
// table): v_0 = 2^31, v_1 = 3 * 2^29, v_k = v_{k-1} ^ v_{k-2} ^ (v_{k-2} >> 2).
SobolDimensionTable sobolDimension2() {
  uint32_t v[32];
  v[0] = 1U << 31;
  v[1] = 3U << 29;
  for (int k = 2; k < 32; ++k) v[k] = v[k - 1] ^ v[k - 2] ^ (v[k - 2] >> 2);
  return SobolDimensionTable(v);
}
const SobolDimensionTable kSobol2 = sobolDimension2();

constexpr uint32_t kShuffleSalt = 0x5f356495U;
constexpr uint32_t kScrambleSalt = 0x2c1b3c6dU;
constexpr uint32_t kCounterSalt = 0x7a3f9e1bU;

// Counter-based value of dimension `dim` of the sample whose key is `key`: the dimension is
// mixed on its own first (independent of the key), then with the key.
uint32_t counterBits(uint32_t key, uint32_t dim) {
  return mix32(key ^ mix32(dim * 0x9e3779b9U + kCounterSalt));
}

// Burley 2020, section 4: shuffle the index with a nested uniform scramble, take the first
// two Sobol dimensions at the shuffled index (dimension 0 is the bit reversal), scramble each.
// Takes the index bit-reversed (shared by all pairs of a sample). With `third`, also Sobol
// dimension 2 at the same shuffled index, scrambled with seedZ (one shuffle for the three).
Sample2 sobolPair(uint32_t reversedIndex, uint32_t shuffleSeed, uint32_t seedX, uint32_t seedY,
                  float* third = nullptr, uint32_t seedZ = 0) {
  const uint32_t shuffled = scrambleReversed(reversedIndex, shuffleSeed);
  if (third) *third = bitsToUnitFloat(scrambleReversed(kSobol2.reversed(shuffled), seedZ));
  return {bitsToUnitFloat(scrambleReversed(shuffled, seedX)), // reverse(reverse(shuffled))
          bitsToUnitFloat(scrambleReversed(kSobol1.reversed(shuffled), seedY))};
}

// Scrambling seeds of the third coordinates and counter dimensions of the independent ones:
// numbered after every pair's two dimensions.
constexpr uint32_t kThirdDimension = 2 * kSobolPairs;
constexpr uint32_t kCounterThirdDimension = 0xffffff00U;

uint32_t shuffleSeed(uint32_t pixel, uint32_t pair, uint32_t seed) {
  return hash4(pixel, pair, seed, kShuffleSalt);
}
uint32_t scrambleSeed(uint32_t pixel, uint32_t dim, uint32_t seed) {
  return hash4(pixel, dim, seed, kScrambleSalt);
}
uint32_t counterKey(uint32_t pixel, uint32_t index, uint32_t seed) {
  return hash4(pixel, index, seed, kCounterSalt);
}

} // namespace

Sample2 samplePair(SamplerKind kind, uint32_t pixel, uint32_t index, uint32_t pair, uint32_t seed) {
  if (kind == SamplerKind::Independent || pair >= kSobolPairs) {
    const uint32_t key = counterKey(pixel, index, seed);
    return {bitsToUnitFloat(counterBits(key, 2 * pair)),
            bitsToUnitFloat(counterBits(key, 2 * pair + 1))};
  }
  return sobolPair(reverseBits(index), shuffleSeed(pixel, pair, seed),
                   scrambleSeed(pixel, 2 * pair, seed), scrambleSeed(pixel, 2 * pair + 1, seed));
}

float sampleValue(SamplerKind kind, uint32_t pixel, uint32_t index, uint32_t dim, uint32_t seed) {
  const Sample2 s = samplePair(kind, pixel, index, dim / 2, seed);
  return (dim & 1U) ? s.v : s.u;
}

PixelSequence::PixelSequence(SamplerKind kind, uint32_t pixel, uint32_t seed)
    : sobol_(kind == SamplerKind::SobolOwen), pixel_(pixel), seed_(seed) {
  for (uint32_t p = 0; p < kSobolPairs; ++p) {
    shuffle_[p] = sobol_ ? shuffleSeed(pixel, p, seed) : 0;
    scramble_[p][0] = sobol_ ? scrambleSeed(pixel, 2 * p, seed) : 0;
    scramble_[p][1] = sobol_ ? scrambleSeed(pixel, 2 * p + 1, seed) : 0;
    scramble_[p][2] = sobol_ ? scrambleSeed(pixel, kThirdDimension + p, seed) : 0;
  }
}

PixelSequence::SampleId PixelSequence::sample(uint32_t index) const {
  return {reverseBits(index), counterKey(pixel_, index, seed_)};
}

Sample2 PixelSequence::pair(const SampleId& id, uint32_t pair) const {
  if (!sobol_ || pair >= kSobolPairs)
    return {bitsToUnitFloat(counterBits(id.key, 2 * pair)),
            bitsToUnitFloat(counterBits(id.key, 2 * pair + 1))};
  return sobolPair(id.reversedIndex, shuffle_[pair], scramble_[pair][0], scramble_[pair][1]);
}

Sample2 PixelSequence::pairWithThird(const SampleId& id, uint32_t pair, float& third) const {
  if (!sobol_ || pair >= kSobolPairs) {
    third = bitsToUnitFloat(counterBits(id.key, kCounterThirdDimension + pair));
    return this->pair(id, pair);
  }
  return sobolPair(id.reversedIndex, shuffle_[pair], scramble_[pair][0], scramble_[pair][1], &third,
                   scramble_[pair][2]);
}

float sampleThird(SamplerKind kind, uint32_t pixel, uint32_t index, uint32_t pair, uint32_t seed) {
  const PixelSequence sequence(kind, pixel, seed);
  float third = 0;
  sequence.pairWithThird(sequence.sample(index), pair, third);
  return third;
}

} // namespace nx
