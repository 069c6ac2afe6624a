#include <gtest/gtest.h>

#include "core/frame.h"
#include "core/hash.h"
#include "core/math_util.h"

namespace nx {
namespace {

void expectOrthonormal(const Frame& f) {
  EXPECT_NEAR(length(f.s), 1.0f, 1e-5f);
  EXPECT_NEAR(length(f.t), 1.0f, 1e-5f);
  EXPECT_NEAR(dot(f.s, f.t), 0.0f, 1e-5f);
  EXPECT_NEAR(dot(f.s, f.n), 0.0f, 1e-5f);
  EXPECT_NEAR(dot(f.t, f.n), 0.0f, 1e-5f);
  // Right-handed: s x t = n.
  const Vec3 c = cross(f.s, f.t);
  EXPECT_NEAR(c.x, f.n.x, 1e-5f);
  EXPECT_NEAR(c.y, f.n.y, 1e-5f);
  EXPECT_NEAR(c.z, f.n.z, 1e-5f);
}

TEST(Frame, AxisAlignedNormalsIncludingMinusZ) {
  for (const Vec3 n : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0, -1, 0),
                       normalize(Vec3(1e-8f, 0, -1))})
    expectOrthonormal(Frame::fromNormal(n));
}

TEST(Frame, RandomNormalsRoundTrip) {
  for (uint32_t i = 0; i < 2000; ++i) {
    const Vec3 n = normalize(Vec3(bitsToUnitFloat(hash4(i, 1, 0, 0)) - 0.5f,
                                  bitsToUnitFloat(hash4(i, 2, 0, 0)) - 0.5f,
                                  bitsToUnitFloat(hash4(i, 3, 0, 0)) - 0.5f));
    const Frame f = Frame::fromNormal(n);
    expectOrthonormal(f);
    const Vec3 v(0.3f, -0.7f, 0.2f);
    const Vec3 back = f.toWorld(f.toLocal(v));
    EXPECT_NEAR(back.x, v.x, 1e-5f);
    EXPECT_NEAR(back.y, v.y, 1e-5f);
    EXPECT_NEAR(back.z, v.z, 1e-5f);
    EXPECT_NEAR(f.toLocal(n).z, 1.0f, 1e-5f);
  }
}

TEST(Vec3, BasicAlgebra) {
  const Vec3 a(1, 2, 3), b(4, -5, 6);
  EXPECT_FLOAT_EQ(dot(a, b), 12.0f);
  EXPECT_EQ(cross(Vec3(1, 0, 0), Vec3(0, 1, 0)), Vec3(0, 0, 1));
  EXPECT_EQ(a + b, Vec3(5, -3, 9));
  EXPECT_EQ(a - b, Vec3(-3, 7, -3));
  EXPECT_FLOAT_EQ(length(Vec3(3, 4, 0)), 5.0f);
  EXPECT_FALSE(isFinite(Vec3(0, INFINITY, 0)));
}

} // namespace
} // namespace nx
