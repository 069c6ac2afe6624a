#pragma once
// A subdivided icosahedron on a sphere: a closed, consistently wound test mesh (a lab's
// spherical lamp as a mesh).

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "core/triangle_mesh.h"

namespace nx::test {

/// Vertices and outward-wound faces of a unit icosahedron subdivided `levels` times, pushed
/// onto the sphere of radius r at c (20 * 4^levels triangles, shared vertices).
struct IcosphereData {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> faces;
};

inline IcosphereData icosphereData(int levels, double r = 1, const Vec3d& c = Vec3d(0, 0, 0)) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                          {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                          {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (Vec3d& p : v) p = normalize(p);
  for (int l = 0; l < levels; ++l) {
    std::vector<std::array<int, 3>> next;
    std::map<std::pair<int, int>, int> middleOf;
    const auto middle = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      if (const auto it = middleOf.find(key); it != middleOf.end()) return it->second;
      v.push_back(normalize(v[static_cast<size_t>(a)] + v[static_cast<size_t>(b)]));
      return middleOf[key] = static_cast<int>(v.size()) - 1;
    };
    for (const auto& tri : f) {
      const int ab = middle(tri[0], tri[1]), bc = middle(tri[1], tri[2]),
                ca = middle(tri[2], tri[0]);
      next.push_back({tri[0], ab, ca});
      next.push_back({tri[1], bc, ab});
      next.push_back({tri[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  IcosphereData d;
  for (const Vec3d& p : v) d.vertices.push_back(Vec3(c + p * r));
  d.faces = std::move(f);
  return d;
}

/// The icosphere as a mesh.
inline TriangleMesh icosphere(int levels, double r = 1, const Vec3d& c = Vec3d(0, 0, 0)) {
  const IcosphereData d = icosphereData(levels, r, c);
  TriangleMesh m;
  for (const Vec3& p : d.vertices) m.addVertex(p);
  for (const auto& tri : d.faces)
    m.addTriangle(static_cast<uint32_t>(tri[0]), static_cast<uint32_t>(tri[1]),
                  static_cast<uint32_t>(tri[2]));
  return m;
}

} // namespace nx::test
