#include <gtest/gtest.h>

#include <array>
#include <map>
#include <set>

#include "core/sampler.h"
#include "support/statistics.h"

namespace nx {
namespace {

const SamplerKind kKinds[] = {SamplerKind::SobolOwen, SamplerKind::Independent};

TEST(Sampler, PureFunctionOfItsFourArguments) {
  for (SamplerKind k : kKinds) {
    EXPECT_EQ(sampleValue(k, 7, 11, 3, 42), sampleValue(k, 7, 11, 3, 42));
    // Changing any one argument changes the value.
    const float v = sampleValue(k, 7, 11, 3, 42);
    EXPECT_NE(v, sampleValue(k, 8, 11, 3, 42));
    EXPECT_NE(v, sampleValue(k, 7, 12, 3, 42));
    EXPECT_NE(v, sampleValue(k, 7, 11, 4, 42));
    EXPECT_NE(v, sampleValue(k, 7, 11, 3, 43));
  }
}

TEST(Sampler, StreamMatchesDirectValues) {
  for (SamplerKind k : kKinds) {
    const PixelSequence sequence(k, 5, 1);
    PixelSampleStream s(sequence, 9);
    const float a = s.next1D();
    const Sample2 b = s.next2D();
    const float c = s.next1D();
    EXPECT_EQ(a, sampleValue(k, 5, 9, 0, 1));
    EXPECT_EQ(b.u, sampleValue(k, 5, 9, 2, 1));
    EXPECT_EQ(b.v, sampleValue(k, 5, 9, 3, 1));
    EXPECT_EQ(c, sampleValue(k, 5, 9, 1, 1)); // the second coordinate of the first pair
    const float d = s.next1D();
    EXPECT_EQ(d, sampleValue(k, 5, 9, 4, 1));
    // Every pair, Sobol and counter-based, equals the value computed from scratch.
    for (uint32_t pair = 3; pair < 3 * kSobolPairs; ++pair) {
      const Sample2 e = s.next2D(), f = samplePair(k, 5, 9, pair, 1);
      EXPECT_EQ(e.u, f.u);
      EXPECT_EQ(e.v, f.v);
    }
  }
}

// Chi-square test of 1D uniformity of one dimension over many pixels and sample indices.
TEST(Sampler, OneDimensionIsUniform) {
  for (SamplerKind k : kKinds) {
    for (uint32_t dim : {0u, 1u, 7u, 30u}) {
      const int bins = 256, n = 256 * 400;
      std::vector<double> obs(bins, 0), exp(bins, n / double(bins));
      for (int i = 0; i < n; ++i) {
        const float v =
            sampleValue(k, static_cast<uint32_t>(i / 64), static_cast<uint32_t>(i % 64), dim, 3);
        ASSERT_GE(v, 0.0f);
        ASSERT_LT(v, 1.0f);
        obs[static_cast<int>(v * bins)] += 1;
      }
      const auto [stat, dof] = test::chiSquare(obs, exp);
      EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << "kind " << int(k) << " dim " << dim;
    }
  }
}

// Pairs of dimensions, within one pair and across pairs, are jointly uniform (independent).
TEST(Sampler, PairsOfDimensionsAreJointlyUniform) {
  for (SamplerKind k : kKinds) {
    for (auto [d0, d1] :
         {std::pair{0u, 1u}, std::pair{0u, 2u}, std::pair{1u, 3u}, std::pair{4u, 9u},
          std::pair{12u, 13u}, std::pair{12u, 14u}, std::pair{11u, 12u}, std::pair{15u, 40u}}) {
      const int side = 32, n = side * side * 100;
      std::vector<double> obs(side * side, 0), exp(side * side, n / double(side * side));
      for (int i = 0; i < n; ++i) {
        // Many pixels, few samples each: the pixel-to-pixel decorrelation is what is tested.
        const uint32_t px = static_cast<uint32_t>(i / 16), idx = static_cast<uint32_t>(i % 16);
        const float a = sampleValue(k, px, idx, d0, 9), b = sampleValue(k, px, idx, d1, 9);
        obs[static_cast<int>(a * side) * side + static_cast<int>(b * side)] += 1;
      }
      const auto [stat, dof] = test::chiSquare(obs, exp);
      EXPECT_LT(test::chiSquareZ(stat, dof), 4.0)
          << "kind " << int(k) << " dims " << d0 << "," << d1;
    }
  }
}

// The first 2^m samples of a pixel form a (0,m,2)-net in each dimension pair: every
// elementary interval of area 2^-m holds exactly one point. Independent sampling fails this.
TEST(Sampler, SobolOwenFirstPowerOfTwoSamplesFormNets) {
  for (uint32_t pixel : {0u, 17u, 123456u}) {
    for (uint32_t pair : {0u, 1u, kSobolPairs - 1}) {
      for (int m = 1; m <= 8; ++m) {
        const uint32_t n = 1u << m;
        for (int xBits = 0; xBits <= m; ++xBits) {
          const int yBits = m - xBits;
          std::set<uint32_t> cells;
          for (uint32_t i = 0; i < n; ++i) {
            const Sample2 s = samplePair(SamplerKind::SobolOwen, pixel, i, pair, 77);
            const uint32_t cx = static_cast<uint32_t>(s.u * float(1u << xBits));
            const uint32_t cy = static_cast<uint32_t>(s.v * float(1u << yBits));
            cells.insert(cx * (1u << yBits) + cy);
          }
          EXPECT_EQ(cells.size(), n) << "pixel " << pixel << " pair " << pair << " m " << m;
        }
      }
    }
  }
  // Beyond kSobolPairs the values are independent: no net structure.
  int laterNets = 0;
  for (uint32_t pixel = 0; pixel < 20; ++pixel) {
    std::set<uint32_t> cells;
    for (uint32_t i = 0; i < 16; ++i)
      cells.insert(static_cast<uint32_t>(
          sampleValue(SamplerKind::SobolOwen, pixel, i, 2 * kSobolPairs, 1) * 16));
    laterNets += cells.size() == 16;
  }
  EXPECT_LT(laterNets, 3);
  int independentNets = 0;
  for (uint32_t pixel = 0; pixel < 20; ++pixel) {
    std::set<uint32_t> cells;
    for (uint32_t i = 0; i < 16; ++i)
      cells.insert(
          static_cast<uint32_t>(sampleValue(SamplerKind::Independent, pixel, i, 0, 1) * 16));
    independentNets += cells.size() == 16;
  }
  EXPECT_LT(independentNets, 3);
}

// The third coordinate of a pair (Sobol dimension 2 at the pair's shuffled index): for the
// first 2^m samples of a pixel it is a (0,m,1)-net on its own, with each of the pair's
// coordinates a net of t <= 1 (every elementary interval of area 2^(1-m) holds two points),
// and the three together a (1,m,3)-net (Joe and Kuo's dimensions 1-3); across pixels it is
// uniform and independent of the pair (chi-square). The stream hands it out as the next 1D
// draw after next2DWithThirdPending.
TEST(Sampler, ThirdCoordinateIsStratifiedWithItsPair) {
  // Points of boxes with the given bits per coordinate; each must hold `per` points.
  auto eachBoxHolds = [](const std::vector<std::array<float, 3>>& pts, int bx, int by, int bz,
                         uint32_t per) {
    std::map<uint32_t, uint32_t> counts;
    for (const auto& p : pts) {
      const uint32_t cx = static_cast<uint32_t>(p[0] * float(1u << bx));
      const uint32_t cy = static_cast<uint32_t>(p[1] * float(1u << by));
      const uint32_t cz = static_cast<uint32_t>(p[2] * float(1u << bz));
      ++counts[(cx << 20) | (cy << 10) | cz];
    }
    for (const auto& [cell, c] : counts)
      if (c != per) return false;
    return counts.size() == pts.size() / per;
  };
  for (uint32_t pixel : {0u, 17u, 123456u})
    for (uint32_t pair : {0u, kSobolPairs - 1})
      for (int m = 1; m <= 8; ++m) {
        const uint32_t n = 1u << m;
        std::vector<std::array<float, 3>> pts;
        for (uint32_t i = 0; i < n; ++i) {
          const Sample2 s = samplePair(SamplerKind::SobolOwen, pixel, i, pair, 77);
          pts.push_back({s.u, s.v, sampleThird(SamplerKind::SobolOwen, pixel, i, pair, 77)});
        }
        EXPECT_TRUE(eachBoxHolds(pts, 0, 0, m, 1)) << "alone, m " << m;
        for (int a = 0; a < m; ++a) {
          EXPECT_TRUE(eachBoxHolds(pts, a, 0, m - 1 - a, 2)) << "with u, m " << m << " a " << a;
          EXPECT_TRUE(eachBoxHolds(pts, 0, a, m - 1 - a, 2)) << "with v, m " << m << " a " << a;
          for (int b = 0; a + b < m; ++b)
            EXPECT_TRUE(eachBoxHolds(pts, a, b, m - 1 - a - b, 2))
                << "all three, m " << m << " " << a << "," << b;
        }
      }
  for (SamplerKind k : kKinds) {
    const int side = 16, n = side * side * side * 40;
    std::vector<double> obs(side * side * side, 0), exp(obs.size(), n / double(obs.size()));
    for (int i = 0; i < n; ++i) {
      const uint32_t px = static_cast<uint32_t>(i / 16), idx = static_cast<uint32_t>(i % 16);
      const Sample2 s = samplePair(k, px, idx, 0, 9);
      const float w = sampleThird(k, px, idx, 0, 9);
      obs[(static_cast<size_t>(s.u * side) * side + static_cast<size_t>(s.v * side)) * side +
          static_cast<size_t>(w * side)] += 1;
    }
    const auto [stat, dof] = test::chiSquare(obs, exp);
    EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << "kind " << int(k);
  }
  const PixelSequence sequence(SamplerKind::SobolOwen, 5, 3);
  PixelSampleStream stream(sequence, 6);
  const Sample2 first = stream.next2DWithThirdPending();
  const Sample2 second = stream.next2D();
  const float third = stream.next1D();
  EXPECT_EQ(first.u, samplePair(SamplerKind::SobolOwen, 5, 6, 0, 3).u);
  EXPECT_EQ(second.v, samplePair(SamplerKind::SobolOwen, 5, 6, 1, 3).v);
  EXPECT_EQ(third, sampleThird(SamplerKind::SobolOwen, 5, 6, 0, 3));
  EXPECT_EQ(stream.next1D(), samplePair(SamplerKind::SobolOwen, 5, 6, 2, 3).u);
}

// Sample index ranges of a pixel are disjoint parts of one sequence (farm splits).
TEST(Sampler, SampleRangesAreTheSameSequence) {
  std::vector<float> whole, parts;
  for (uint32_t i = 0; i < 64; ++i)
    whole.push_back(sampleValue(SamplerKind::SobolOwen, 3, i, 2, 5));
  for (uint32_t i = 32; i < 64; ++i)
    parts.push_back(sampleValue(SamplerKind::SobolOwen, 3, i, 2, 5));
  EXPECT_TRUE(std::equal(parts.begin(), parts.end(), whole.begin() + 32));
}

} // namespace
} // namespace nx
