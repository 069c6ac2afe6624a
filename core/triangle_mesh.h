#pragma once
// An indexed triangle mesh in single precision: plain buffers (the mesh reader fills them; the
// geometry (accel/) lets Embree read them in place), and one triangle's corners in double.

#include <cstdint>
#include <string>
#include <vector>

#include "core/matrix3.h"
#include "core/vec3.h"

namespace nx {

/// Peak memory of a mesh per face and per vertex (bytes): for a file, the mesh library's
/// structures, its triangulation and vertex joining, and the mesh built from them (measured:
/// docs/reliability.md, round 3); for rows given inline or from Python, the same bound covers
/// the mesh and its acceleration structure. Checked against the memory budget before either is
/// built.
inline constexpr double kMeshBytesPerFace = 400;
inline constexpr double kMeshBytesPerVertex = 100;

/// A triangle with vertices a, b, c (front face counter-clockwise seen from its normal
/// (b - a) x (c - a)).
struct TriangleShape {
  Vec3d a, b, c;
  /// Its area |(b - a) x (c - a)| / 2.
  double area() const { return 0.5 * length(cross(b - a, c - a)); }
};

/// Largest coordinate a mesh vertex may have (as for the scene's own shapes: far below
/// Embree's limit of about 1.8e18, beyond which it drops primitives silently).
inline constexpr float kMaxMeshCoordinate = 1e12f;

/// Vertex positions, triangle indices and optional per-vertex normals and uv. The position
/// buffer carries one float of padding after the last vertex, because Embree reads vertices as
/// 16-byte vectors (its documented requirement for shared vertex buffers).
class TriangleMesh {
public:
  /// An empty mesh.
  TriangleMesh() { xyz_.push_back(0); }

  /// A mesh of separate triangles (three vertices each, no normals, uv of (0,0), (1,0), (1,1)).
  static TriangleMesh fromTriangles(const std::vector<TriangleShape>& triangles);

  /// Appends a vertex; returns its index.
  uint32_t addVertex(const Vec3& p);
  /// Appends a triangle of three vertex indices (checked by validate()).
  void addTriangle(uint32_t a, uint32_t b, uint32_t c) {
    indices_.insert(indices_.end(), {a, b, c});
  }
  /// Sets per-vertex normals (3 floats per vertex) and uv (2 floats per vertex); either may be
  /// empty.
  void setAttributes(std::vector<float> normals, std::vector<float> uv);
  /// Reserves room for `vertices` vertices and `triangles` triangles.
  void reserve(size_t vertices, size_t triangles);

  /// Number of vertices.
  size_t vertexCount() const { return (xyz_.size() - 1) / 3; }
  /// Number of triangles.
  size_t triangleCount() const { return indices_.size() / 3; }
  /// Position of vertex i.
  Vec3 position(uint32_t i) const { return {xyz_[3 * i], xyz_[3 * i + 1], xyz_[3 * i + 2]}; }
  /// Vertex indices of triangle t.
  const uint32_t* triangle(size_t t) const { return &indices_[3 * t]; }
  /// The corners of triangle t in double precision (exact: they are floats).
  TriangleShape corners(size_t t) const;
  /// The sum of its triangles' areas (one face each), in double precision.
  double area() const;
  /// True when the mesh has per-vertex normals / uv.
  bool hasNormals() const { return !normals_.empty(); }
  bool hasUv() const { return !uv_.empty(); }
  /// Normal of vertex i (unnormalised, as stored); only with hasNormals().
  Vec3 normal(uint32_t i) const {
    return {normals_[3 * i], normals_[3 * i + 1], normals_[3 * i + 2]};
  }
  /// uv of vertex i; only with hasUv().
  void uv(uint32_t i, float& u, float& v) const { u = uv_[2 * i], v = uv_[2 * i + 1]; }

  /// The buffers as Embree reads them.
  const float* positionData() const { return xyz_.data(); }
  const uint32_t* indexData() const { return indices_.data(); }

  /// Bytes the mesh holds (buffers' capacities).
  size_t bytes() const;

  /// Applies an affine map p -> M p + t; normals by the inverse transpose (renormalised).
  /// M must be non-singular.
  void transform(const Matrix3& m, const Vec3d& t);

  /// Empty if every index is in range, every position finite and within kMaxMeshCoordinate,
  /// every attribute finite and some triangle has a non-zero area; else what is wrong
  /// ("triangle 12 refers to vertex 99 of 40").
  std::string validate() const;
  /// How many triangles have zero area (never hit; validate() refuses a mesh of only these).
  size_t zeroAreaTriangles() const;
  /// Whether both hold the same vertices (positions, normals, uv) and triangles, exactly.
  bool operator==(const TriangleMesh&) const = default;

private:
  std::vector<float> xyz_; ///< 3 floats per vertex + 1 float of padding
  std::vector<uint32_t> indices_;
  std::vector<float> normals_, uv_;
};

} // namespace nx
