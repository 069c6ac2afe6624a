#pragma once
// A moving mesh's outline seen from a point: its silhouette edges (those between a triangle
// facing the point and one facing away, and its border edges), where visibility changes as the
// mesh or the point moves, and on a flat-shaded mesh every edge seen (the shading jumps there); the
// boundary terms of shape derivatives sample them (primary_boundary.h on the film, the path
// tracer's direction boundary at each vertex).

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/triangle_mesh.h"
#include "integrators/gradients/shape_tangents.h"

namespace nx {

/// True when edge e is on the mesh's outline seen from p: a border edge, or one whose two
/// triangles face p on different sides.
inline bool silhouetteEdge(const TriangleMesh& mesh, const MeshEdge& e, const Vec3d& p) {
  if (e.face1 < 0) return true;
  auto facing = [&](int64_t f) {
    const TriangleShape t = mesh.corners(static_cast<size_t>(f));
    return dot(cross(t.b - t.a, t.c - t.a), p - t.a) > 0;
  };
  return facing(e.face0) != facing(e.face1);
}

/// True when edge e can separate two different radiances seen from p: a silhouette edge; and
/// on a flat-shaded mesh (no vertex normals: its faces' normals jump at every edge) any edge
/// of a triangle facing p between faces that are not coplanar (a quad's diagonal is not).
inline bool outlineEdge(const TriangleMesh& mesh, const MeshEdge& e, const Vec3d& p) {
  if (silhouetteEdge(mesh, e, p)) return true;
  if (mesh.hasNormals()) return false;
  auto normal = [&](int64_t f) {
    const TriangleShape t = mesh.corners(static_cast<size_t>(f));
    return Vec3d(cross(t.b - t.a, t.c - t.a));
  };
  const Vec3d n0 = normal(e.face0), n1 = normal(e.face1);
  if (length(cross(n0, n1)) <= 1e-9 * length(n0) * length(n1)) return false;
  const TriangleShape t = mesh.corners(static_cast<size_t>(e.face0));
  return dot(n0, p - Vec3d(t.a)) > 0; // (both face the same way here)
}

/// The silhouette edges seen from a fixed point, chosen in proportion to a length each.
struct EdgeSet {
  std::vector<uint32_t> edges; ///< indices into MeshMotion::edges
  std::vector<double> cdf;     ///< running sums of the lengths
  /// The sum of the lengths.
  double total() const { return cdf.empty() ? 0 : cdf.back(); }
  /// Adds edge e of length `length`.
  void add(uint32_t e, double length) {
    edges.push_back(e);
    cdf.push_back(total() + length);
  }
  /// The edge chosen by u in [0, 1) and its length.
  uint32_t choose(double u, double& length) const {
    const double x = u * total();
    const size_t i = std::min<size_t>(
        static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(), x) - cdf.begin()),
        edges.size() - 1);
    length = cdf[i] - (i ? cdf[i - 1] : 0);
    return edges[i];
  }
};

} // namespace nx
