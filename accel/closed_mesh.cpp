// Closed meshes: edge pairing, signed volume, inside test.

#include "accel/closed_mesh.h"

#include <array>
#include <cmath>
#include <map>

namespace nx {

MeshClosure meshClosure(const TriangleMesh& m) {
  MeshClosure c;
  // Vertices matched by position (files often split vertices along uv or normal seams).
  std::map<std::array<float, 3>, uint32_t> byPosition;
  auto id = [&](uint32_t v) {
    const Vec3 p = m.position(v);
    return byPosition.emplace(std::array<float, 3>{p.x, p.y, p.z}, byPosition.size()).first->second;
  };
  // Per undirected edge: uses from its lower to its higher id, and back.
  std::map<std::pair<uint32_t, uint32_t>, std::array<int, 2>> edges;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const uint32_t* tri = m.triangle(t);
    const uint32_t v[3] = {id(tri[0]), id(tri[1]), id(tri[2])};
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = v[k], b = v[(k + 1) % 3];
      if (a == b) continue; // a degenerate triangle's collapsed edge
      auto& e = edges[{std::min(a, b), std::max(a, b)}];
      ++e[a < b ? 0 : 1];
    }
    const TriangleShape s = m.corners(t);
    c.volume += dot(s.a, cross(s.b, s.c)) / 6;
  }
  for (const auto& [edge, uses] : edges) {
    if (uses[0] == 1 && uses[1] == 1) continue;
    const int n = uses[0] + uses[1];
    c.problem = n == 1   ? "an edge used by one triangle only (a hole)"
                : n == 2 ? "two neighbouring triangles wound in opposite directions"
                         : "an edge shared by " + std::to_string(n) + " triangles";
    return c;
  }
  c.closed = !edges.empty();
  if (!c.closed) c.problem = "no triangles";
  return c;
}

bool insideClosedMesh(const TriangleMesh& m, const Vec3d& p) {
  const Vec3d d = Vec3d(0.31415926, 0.57721566, 0.75510257);
  int crossings = 0;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    // Moller-Trumbore in double precision.
    const TriangleShape s = m.corners(t);
    const Vec3d e1 = s.b - s.a, e2 = s.c - s.a, q = cross(d, e2);
    const double det = dot(e1, q);
    if (std::abs(det) < 1e-300) continue;
    const Vec3d r = p - s.a;
    const double u = dot(r, q) / det;
    if (u < 0 || u > 1) continue;
    const Vec3d w = cross(r, e1);
    const double v = dot(d, w) / det;
    if (v < 0 || u + v > 1) continue;
    if (dot(e2, w) / det > 0) ++crossings;
  }
  return crossings % 2 == 1;
}

} // namespace nx
