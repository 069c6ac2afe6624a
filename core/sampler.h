#pragma once
// Deterministic sample values that depend only on (pixel, sample index, dimension, seed).
//
// Why: the image must not depend on the thread count and a render split over a farm by
// pixels or by sample ranges must merge into the image of one run. Both follow when a
// sample value is a pure function of those four numbers, so there is no generator state.
//
// Two kinds are offered:
// - Independent: a counter-based generator (a hash of the four numbers). Plain Monte
//   Carlo, O(N^-1/2) error, no structure at all: the reference for unbiasedness checks.
// - SobolOwen (default): the first two Sobol dimensions, Owen-scrambled and padded per
//   dimension pair with a hashed index shuffle (B. Burley, "Practical Hash-based Owen
//   Scrambling", JCGT 9(4), 2020), for the first kSobolPairs dimension pairs (wavelengths,
//   pixel position, the first bounces); each pixel's first 2^m samples form a (0,m,2)-net in
//   each of them. Later dimensions, where stratification hardly lowers the error of a path
//   integrand, take the counter-based values, which cost a fraction as much.
//
// The scrambling seeds depend on (pixel, pair, seed) only, so PixelSequence computes them
// once per pixel; the counter-based values hash (pixel, index, seed) once per sample and mix
// in the dimension per value. samplePair() computes the same values from scratch.

#include <cstdint>

namespace nx {

/// Dimension pairs drawn from scrambled Sobol points by SamplerKind::SobolOwen; later pairs
/// are independent (see above).
inline constexpr uint32_t kSobolPairs = 6;

/// Which sequence a render draws its sample values from.
enum class SamplerKind : uint8_t { SobolOwen, Independent };

/// A point of the unit square.
struct Sample2 {
  float u = 0, v = 0;
};

/// Value in [0,1) of dimension `dim` of sample `index` of pixel `pixel`.
float sampleValue(SamplerKind kind, uint32_t pixel, uint32_t index, uint32_t dim, uint32_t seed);

/// Dimensions 2*pair and 2*pair+1 together (they form a (0,2)-sequence for SobolOwen).
Sample2 samplePair(SamplerKind kind, uint32_t pixel, uint32_t index, uint32_t pair, uint32_t seed);

/// The third coordinate of that pair (PixelSequence::pairWithThird).
float sampleThird(SamplerKind kind, uint32_t pixel, uint32_t index, uint32_t pair, uint32_t seed);

/// The sequence of one (pixel, seed): its scrambling seeds, computed once and shared by all
/// of the pixel's samples.
class PixelSequence {
public:
  /// The sequence of `pixel` for `seed`.
  PixelSequence(SamplerKind kind, uint32_t pixel, uint32_t seed);

  /// What all draws of one sample share, computed once per sample.
  struct SampleId {
    uint32_t reversedIndex; ///< the sample index, bit-reversed (where Sobol points start)
    uint32_t key;           ///< hash of (pixel, index, seed) for the counter-based dimensions
  };
  /// The shared values of sample `index`.
  SampleId sample(uint32_t index) const;
  /// Dimensions 2*pair and 2*pair+1 of the sample: equal to samplePair(kind, pixel, index,
  /// pair, seed).
  Sample2 pair(const SampleId& id, uint32_t pair) const;
  /// The pair, and in `third` its third coordinate: Sobol dimension 2 at the pair's shuffled
  /// index, with a scrambling of its own (SobolOwen; for the first 2^m samples the three
  /// coordinates form a (1,m,3)-net, each two a net of t <= 1), else a counter-based value.
  Sample2 pairWithThird(const SampleId& id, uint32_t pair, float& third) const;

private:
  bool sobol_;
  uint32_t pixel_, seed_;
  uint32_t shuffle_[kSobolPairs];     ///< index shuffle seed per Sobol pair
  uint32_t scramble_[kSobolPairs][3]; ///< Owen scrambling seed per Sobol dimension (and third)
};

/// The sample values of one (pixel, sample index), handed out in order. A 2D draw takes a
/// fresh dimension pair; two successive 1D draws share one pair (its two coordinates).
class PixelSampleStream {
public:
  /// Starts at dimension pair 0 of sample `index` of the sequence (which must outlive it).
  PixelSampleStream(const PixelSequence& sequence, uint32_t index)
      : sequence_(&sequence), id_(sequence.sample(index)) {}

  /// Next value in [0,1).
  float next1D() {
    if (pending_) {
      pending_ = false;
      return pendingValue_;
    }
    const Sample2 s = next2D();
    pending_ = true;
    pendingValue_ = s.v;
    return s.u;
  }
  /// Next point in [0,1)^2.
  Sample2 next2D() { return sequence_->pair(id_, pair_++); }
  /// The next pair's two coordinates, and its third (Sobol dimension 2 at the same shuffled
  /// index) left as the next 1D draw: three coordinates stratified together, e.g. a sample's
  /// wavelengths (two) and the path's first decision, as one coordinate's wavelengths share
  /// their pair with that decision (next1D).
  Sample2 next2DWithThirdPending() {
    pending_ = true;
    return sequence_->pairWithThird(id_, pair_++, pendingValue_);
  }

private:
  const PixelSequence* sequence_;
  PixelSequence::SampleId id_;
  uint32_t pair_ = 0;
  bool pending_ = false; ///< the second coordinate of the last 1D pair is unused
  float pendingValue_ = 0;
};

} // namespace nx
