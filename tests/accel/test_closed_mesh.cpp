// Closed meshes: edge pairing, signed volume and the inside test.

#include <gtest/gtest.h>

#include "accel/closed_mesh.h"

namespace nx {
namespace {

// A cube [-1, 1]^3 as 12 triangles, wound outward (or inward), optionally without its +x face,
// with the vertices of each face duplicated (as files split them at seams).
TriangleMesh cube(bool inward, bool open) {
  const Vec3 v[8] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                     {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  TriangleMesh m;
  for (int f = 0; f < (open ? 5 : 6); ++f) {
    uint32_t q[4];
    for (int k = 0; k < 4; ++k) q[k] = m.addVertex(v[faces[f][k]]);
    if (inward) {
      m.addTriangle(q[0], q[2], q[1]);
      m.addTriangle(q[0], q[3], q[2]);
    } else {
      m.addTriangle(q[0], q[1], q[2]);
      m.addTriangle(q[0], q[2], q[3]);
    }
  }
  return m;
}

TEST(ClosedMesh, VolumeSignAndHoles) {
  const MeshClosure out = meshClosure(cube(false, false));
  EXPECT_TRUE(out.closed) << out.problem;
  EXPECT_NEAR(out.volume, 8, 1e-12);
  const MeshClosure in = meshClosure(cube(true, false));
  EXPECT_TRUE(in.closed);
  EXPECT_NEAR(in.volume, -8, 1e-12);
  const MeshClosure open = meshClosure(cube(false, true));
  EXPECT_FALSE(open.closed);
  EXPECT_EQ(open.problem, "an edge used by one triangle only (a hole)");
  // one face flipped: its edges run the same way as their neighbours'
  TriangleMesh flipped = cube(false, true);
  const uint32_t a = flipped.addVertex({1, -1, -1}), b = flipped.addVertex({1, 1, -1}),
                 c = flipped.addVertex({1, 1, 1}), d = flipped.addVertex({1, -1, 1});
  flipped.addTriangle(a, c, b);
  flipped.addTriangle(a, d, c);
  EXPECT_EQ(meshClosure(flipped).problem,
            "two neighbouring triangles wound in opposite directions");
}

TEST(ClosedMesh, InsideTest) {
  const TriangleMesh m = cube(false, false);
  EXPECT_TRUE(insideClosedMesh(m, {0, 0, 0}));
  EXPECT_TRUE(insideClosedMesh(m, {0.99, -0.99, 0.5}));
  EXPECT_FALSE(insideClosedMesh(m, {1.01, 0, 0}));
  EXPECT_FALSE(insideClosedMesh(m, {0, 0, -5}));
}

} // namespace
} // namespace nx
