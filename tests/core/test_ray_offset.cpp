#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/hash.h"
#include "core/ray_offset.h"

namespace nx {
namespace {

// nextFloatUp / nextFloatDown agree with std::nextafter everywhere it matters: zeros of both
// signs, denormals, the largest floats, infinities, and random values of both signs.
TEST(RayOffset, NextFloatMatchesNextafter) {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> values = {0.0f,
                               -0.0f,
                               std::numeric_limits<float>::denorm_min(),
                               -std::numeric_limits<float>::denorm_min(),
                               std::numeric_limits<float>::min(),
                               -std::numeric_limits<float>::min(),
                               std::numeric_limits<float>::max(),
                               -std::numeric_limits<float>::max(),
                               1.0f,
                               -1.0f,
                               inf,
                               -inf};
  for (uint32_t i = 0; i < 100000; ++i) {
    uint32_t bits = hash4(i, 7, 0, 0);
    float f;
    std::memcpy(&f, &bits, sizeof f);
    if (std::isfinite(f)) values.push_back(f);
  }
  for (float v : values) {
    const float up = nextFloatUp(v), down = nextFloatDown(v);
    if (v == inf) {
      EXPECT_EQ(up, inf);
    } else {
      EXPECT_EQ(up, std::nextafter(v, inf)) << v;
      EXPECT_GT(up, v);
    }
    if (v == -inf) {
      EXPECT_EQ(down, -inf);
    } else {
      EXPECT_EQ(down, std::nextafter(v, -inf)) << v;
      EXPECT_LT(down, v);
    }
  }
}

} // namespace
} // namespace nx
