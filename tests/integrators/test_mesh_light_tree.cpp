// Light bounds and the light tree of emitting meshes: the importance's far-field closed form,
// its conservativeness (zero only where nothing can shine), cones holding what they merge, the
// tree's choices against the probabilities it reports (chi-square), back faces of closed meshes
// never chosen from outside, bounded depth on degenerate meshes.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "accel/closed_mesh.h"
#include "core/math_util.h"
#include "integrators/lights/light_bounds.h"
#include "integrators/lights/mesh_light_tree.h"
#include "support/icosphere.h"
#include "support/statistics.h"

namespace nx {
namespace {

// A triangle's bounds as the light tree makes its leaves.
LightBounds boundsOf(const TriangleShape& t, bool flip = false) {
  LightBounds b;
  b.add(Vec3(t.a));
  b.add(Vec3(t.b));
  b.add(Vec3(t.c));
  const Vec3d nd = cross(t.b - t.a, t.c - t.a);
  b.normals = {Vec3(normalize(nd) * (flip ? -1.0 : 1.0)), 1.0f};
  b.power = static_cast<float>(0.5 * length(nd));
  b.planeAnchor = Vec3(t.a); // the plane test, exact for one triangle
  b.planeOffset = 0;
  return b;
}

// Far from a triangle the importance is its point-source value A cos(theta_e) cos(theta_i) / d^2
// (the bound's angles shrink with the distance); facing away it is zero one-sided and the same
// two-sided.
TEST(LightBounds, FarFieldImportanceIsThePointSourceValue) {
  const TriangleShape t{Vec3d(0, 0, 0), Vec3d(0.1, 0, 0), Vec3d(0, 0.1, 0)};
  const LightBounds b = boundsOf(t);
  const Vec3d c = (t.a + t.b + t.c) * (1.0 / 3);
  for (const Vec3d dir : {normalize(Vec3d(0.3, 0.2, 1)), normalize(Vec3d(1, -0.5, 0.4))}) {
    const Vec3d p = c + dir * 1000.0;
    const Vec3d n = normalize(Vec3d(0.2, 0.1, -1));
    const double exact = 0.005 * dir.z * std::abs(dot(n, dir)) / 1e6;
    EXPECT_NEAR(LightCluster(b).importance(Vec3(p), Vec3(n), false), exact, 2e-3 * exact);
    EXPECT_NEAR(LightCluster(b).importance(Vec3(p), Vec3(), false), exact / std::abs(dot(n, dir)),
                2e-3 * exact);
    const Vec3d behind = c - dir * 1000.0;
    EXPECT_EQ(LightCluster(b).importance(Vec3(behind), Vec3(n), false), 0.0f);
    EXPECT_NEAR(LightCluster(b).importance(Vec3(behind), Vec3(n), true), exact, 2e-3 * exact);
  }
}

// Conservative: wherever a point of a triangle faces p (one-sided) the triangle's importance is
// positive, for random triangles, points and receiver normals; the union of random clusters is
// zero only when all of them are, and its cone holds every normal of its members.
TEST(LightBounds, ZeroOnlyWhereNothingFaces) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> x(-1, 1);
  int zeros = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec3d o(x(rng), x(rng), x(rng));
    const double size = std::pow(10.0, 2 * x(rng) - 1);
    const TriangleShape t{o, o + Vec3d(x(rng), x(rng), x(rng)) * size,
                          o + Vec3d(x(rng), x(rng), x(rng)) * size};
    const Vec3d nd = cross(t.b - t.a, t.c - t.a);
    if (!(length(nd) > 1e-6 * size * size)) continue;
    const Vec3d p(2 * x(rng), 2 * x(rng), 2 * x(rng));
    const Vec3 n = normalize(
        Vec3(static_cast<float>(x(rng)), static_cast<float>(x(rng)), static_cast<float>(x(rng))));
    const LightBounds b = boundsOf(t);
    const float importance = LightCluster(b).importance(Vec3(p), n, false);
    bool faces = false;
    for (int s = 0; s < 64 && !faces; ++s) {
      double b1 = (x(rng) + 1) / 2, b2 = (x(rng) + 1) / 2;
      if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
      const Vec3d q = t.a + (t.b - t.a) * b1 + (t.c - t.a) * b2;
      faces = dot(nd, p - q) > 1e-9 * length(nd) * length(p - q);
    }
    if (importance == 0) {
      ++zeros;
      EXPECT_FALSE(faces) << k;
    }
    EXPECT_GT(LightCluster(b).importance(Vec3(p), n, true), 0.0f)
        << k; // two-sided: always some face
  }
  EXPECT_GT(zeros, 500); // the test saw triangles turned away
  // Unions: positive where a member's triangle faces p, and the cone holds each normal.
  for (int k = 0; k < 500; ++k) {
    LightBounds all;
    std::vector<TriangleShape> members;
    for (int m = 0; m < 4; ++m) {
      const Vec3d o(x(rng), x(rng), x(rng));
      const TriangleShape t{o, o + Vec3d(x(rng), x(rng), x(rng)) * 0.2,
                            o + Vec3d(x(rng), x(rng), x(rng)) * 0.2};
      if (!(length(cross(t.b - t.a, t.c - t.a)) > 1e-8)) continue;
      members.push_back(t);
      all = unionOf(all, boundsOf(t));
    }
    if (members.empty()) continue;
    for (const TriangleShape& m : members)
      EXPECT_GE(dot(all.normals.axis, boundsOf(m).normals.axis), all.normals.cosSpread - 1e-5f)
          << k;
    const Vec3d p(2 * x(rng), 2 * x(rng), 2 * x(rng));
    bool faces = false;
    for (const TriangleShape& m : members)
      faces = faces || dot(cross(m.b - m.a, m.c - m.a), p - (m.a + m.b + m.c) * (1.0 / 3)) > 0;
    if (faces) {
      EXPECT_GT(LightCluster(all).importance(Vec3(p), Vec3(), false), 0.0f) << k;
    }
  }
}

// The tree's choices follow the probabilities it reports (chi-square over the triangles of a
// 320-triangle icosphere, and a cell for no choice), and choose() reports the same probability
// as probability(): from outside the box, inside it, with and without a receiver normal. Both
// faces emitting (inside the box) the probabilities sum to 1; from outside, some walks end
// where a cluster's bound was positive but none of its triangles faces the point (no sample,
// no bias: the probabilities sum to less than 1).
TEST(MeshLightTree, ChoicesFollowTheirProbabilities) {
  const TriangleMesh mesh = test::icosphere(2, 0.5, Vec3d(0.2, 0.1, 0));
  ASSERT_EQ(mesh.triangleCount(), 320u);
  const MeshClosure closure = meshClosure(mesh);
  ASSERT_TRUE(closure.closed);
  const MeshLightTree tree(mesh, closure.volume > 0 ? 1 : -1);
  const Vec3 points[] = {Vec3(1.5f, 0.3f, -0.4f), Vec3(0.25f, 0.2f, 0.05f),
                         Vec3(0.2f, -0.5f, 0.0f)};
  const Vec3 normals[] = {Vec3(), normalize(Vec3(-1, 0.2f, 0.1f)), Vec3(0, 1, 0)};
  for (int c = 0; c < 3; ++c) {
    const Vec3 p = points[c], n = normals[c];
    std::vector<double> expected(321), observed(321, 0);
    double total = 0;
    for (uint32_t t = 0; t < 320; ++t) total += expected[t] = tree.probability(t, p, n);
    if (tree.oneSidedAt(p)) {
      // Walks that end in a triangle end in one facing p: at least twice as often as a
      // choice by area would (facing triangles hold 32% and 8% of the area here).
      double facingArea = 0, area = 0;
      for (uint32_t t = 0; t < 320; ++t) {
        const TriangleShape tri = mesh.corners(t);
        const Vec3d nd = cross(tri.b - tri.a, tri.c - tri.a) * (closure.volume > 0 ? 1.0 : -1.0);
        area += length(nd);
        if (dot(nd, Vec3d(p) - tri.a) > 0) facingArea += length(nd);
      }
      EXPECT_GT(total, 2 * facingArea / area) << c;
      EXPECT_LE(total, 1 + 1e-9) << c;
    } else {
      EXPECT_NEAR(total, 1.0, 1e-9) << c;
    }
    expected[320] = std::max(0.0, 1 - total);
    const int samples = 200000;
    for (double& e : expected) e *= samples;
    std::mt19937 rng(7 + c);
    std::uniform_real_distribution<double> u01(0, 1);
    for (int k = 0; k < samples; ++k) {
      double probability = 0;
      const int t = tree.choose(p, n, u01(rng), probability);
      if (t < 0) {
        observed[320] += 1;
        continue;
      }
      if (k % 101 == 0) {
        EXPECT_NEAR(probability, tree.probability(static_cast<uint32_t>(t), p, n),
                    1e-9 * probability);
      }
      observed[static_cast<size_t>(t)] += 1;
    }
    const auto [stat, dof] = test::chiSquare(observed, expected);
    EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << c;
  }
}

// From outside a closed mesh's box no triangle turned away is ever chosen (they can only be
// seen from inside), and every one turned towards the point may be; an open mesh (the same
// sphere less one triangle) and a point inside the box keep both faces of every triangle.
TEST(MeshLightTree, ClosedMeshesSeenFromOutsideSkipTheirBackFaces) {
  const TriangleMesh closed = test::icosphere(2);
  const MeshClosure closure = meshClosure(closed);
  ASSERT_TRUE(closure.closed);
  const int sign = closure.volume > 0 ? 1 : -1;
  const MeshLightTree tree(closed, sign);
  TriangleMesh open;
  for (uint32_t v = 0; v < closed.vertexCount(); ++v) open.addVertex(closed.position(v));
  for (size_t t = 1; t < closed.triangleCount(); ++t) {
    const uint32_t* i = closed.triangle(t);
    open.addTriangle(i[0], i[1], i[2]);
  }
  ASSERT_FALSE(meshClosure(open).closed);
  const MeshLightTree openTree(open, 0);
  const Vec3 p(2.5f, 0.7f, -1.1f);
  EXPECT_TRUE(tree.oneSidedAt(p));
  EXPECT_FALSE(openTree.oneSidedAt(p));
  EXPECT_FALSE(tree.oneSidedAt(Vec3(0.9f, 0, 0))); // inside the box
  int away = 0;
  for (uint32_t t = 0; t < closed.triangleCount(); ++t) {
    const TriangleShape c = closed.corners(t);
    const Vec3d outward = cross(c.b - c.a, c.c - c.a) * double(sign);
    const bool facing = dot(outward, Vec3d(p) - c.a) > 0;
    away += facing ? 0 : 1;
    if (facing) {
      EXPECT_GT(tree.probability(t, p, Vec3()), 0) << t;
    } else {
      EXPECT_EQ(tree.probability(t, p, Vec3()), 0) << t;
    }
    EXPECT_GT(tree.probability(t, Vec3(0.9f, 0, 0), Vec3()), 0) << t;
    if (t > 0) {
      EXPECT_GT(openTree.probability(static_cast<uint32_t>(t - 1), p, Vec3()), 0) << t;
    }
  }
  EXPECT_GT(away, 100);
}

// Degenerate meshes keep the tree shallow: triangles sharing one centroid, and a row of
// triangles at exponentially growing spacing (the heuristic's worst case), stay within the
// heuristic's depth plus a balanced tree's (binary levels, two per 4-wide level); every
// triangle keeps a chance.
TEST(MeshLightTree, DepthStaysBoundedOnDegenerateMeshes) {
  std::vector<TriangleShape> same, row;
  for (int i = 0; i < 5000; ++i) {
    const double a = 0.001 * i;
    same.push_back({Vec3d(std::cos(a), std::sin(a), 0), Vec3d(-std::cos(a), -std::sin(a), 0.5),
                    Vec3d(0, 0, -0.5)});
    const double x = std::pow(1.003, i); // up to 3e6
    row.push_back({Vec3d(x, 0, 0), Vec3d(x * 1.001, 0, 0), Vec3d(x, 1e-3 * x, 0)});
  }
  for (const auto* triangles : {&same, &row}) {
    const MeshLightTree tree(TriangleMesh::fromTriangles(*triangles), 0);
    EXPECT_LE(tree.depth(), (48 + 14) / 2 + 1);
    double total = 0;
    for (uint32_t t = 0; t < triangles->size(); ++t) {
      const double chance = tree.probability(t, Vec3(0.3f, 0.2f, 2), Vec3());
      EXPECT_GT(chance, 0) << t;
      total += chance;
    }
    EXPECT_NEAR(total, 1.0, 1e-6);
  }
}

} // namespace
} // namespace nx
