#include "core/triangle_mesh.h"

#include <cmath>
#include <string>

namespace nx {

TriangleMesh TriangleMesh::fromTriangles(const std::vector<TriangleShape>& triangles) {
  TriangleMesh m;
  m.reserve(3 * triangles.size(), triangles.size());
  std::vector<float> uv;
  uv.reserve(6 * triangles.size());
  for (const TriangleShape& t : triangles) {
    const uint32_t a = m.addVertex(Vec3(t.a)), b = m.addVertex(Vec3(t.b)),
                   c = m.addVertex(Vec3(t.c));
    m.addTriangle(a, b, c);
    uv.insert(uv.end(), {0, 0, 1, 0, 1, 1});
  }
  m.setAttributes({}, std::move(uv));
  return m;
}

uint32_t TriangleMesh::addVertex(const Vec3& p) {
  xyz_.back() = p.x; // the padding float becomes x
  xyz_.insert(xyz_.end(), {p.y, p.z, 0.0f});
  return static_cast<uint32_t>(vertexCount() - 1);
}

void TriangleMesh::setAttributes(std::vector<float> normals, std::vector<float> uv) {
  normals_ = std::move(normals);
  uv_ = std::move(uv);
}

void TriangleMesh::reserve(size_t vertices, size_t triangles) {
  xyz_.reserve(3 * vertices + 1);
  indices_.reserve(3 * triangles);
}

TriangleShape TriangleMesh::corners(size_t t) const {
  const uint32_t* i = triangle(t);
  return {Vec3d(position(i[0])), Vec3d(position(i[1])), Vec3d(position(i[2]))};
}

double TriangleMesh::area() const {
  double sum = 0;
  for (size_t t = 0; t < triangleCount(); ++t) sum += corners(t).area();
  return sum;
}

size_t TriangleMesh::bytes() const {
  return sizeof(float) * (xyz_.capacity() + normals_.capacity() + uv_.capacity()) +
         sizeof(uint32_t) * indices_.capacity();
}

void TriangleMesh::transform(const Matrix3& m, const Vec3d& t) {
  for (size_t i = 0; i < vertexCount(); ++i) {
    const Vec3d p(position(static_cast<uint32_t>(i)));
    const Vec3d q(m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + t.x,
                  m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + t.y,
                  m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + t.z);
    xyz_[3 * i] = static_cast<float>(q.x);
    xyz_[3 * i + 1] = static_cast<float>(q.y);
    xyz_[3 * i + 2] = static_cast<float>(q.z);
  }
  if (normals_.empty()) return;
  // Normals transform by the inverse transpose: the cofactor matrix, up to the determinant's
  // sign (a mirroring map keeps normals on the side the winding now gives).
  const Matrix3 inv = inverse(m);
  for (size_t i = 0; i < vertexCount(); ++i) {
    const Vec3d n(normal(static_cast<uint32_t>(i)));
    Vec3d q(inv[0][0] * n.x + inv[1][0] * n.y + inv[2][0] * n.z,
            inv[0][1] * n.x + inv[1][1] * n.y + inv[2][1] * n.z,
            inv[0][2] * n.x + inv[1][2] * n.y + inv[2][2] * n.z);
    const double len = length(q);
    if (len > 0) q = q * (1.0 / len);
    normals_[3 * i] = static_cast<float>(q.x);
    normals_[3 * i + 1] = static_cast<float>(q.y);
    normals_[3 * i + 2] = static_cast<float>(q.z);
  }
}

std::string TriangleMesh::validate() const {
  const size_t n = vertexCount();
  if (triangleCount() == 0) return "no triangles";
  for (size_t i = 0; i + 1 < xyz_.size(); ++i) {
    if (!std::isfinite(xyz_[i])) return "vertex " + std::to_string(i / 3) + " is not finite";
    if (std::abs(xyz_[i]) > kMaxMeshCoordinate)
      return "vertex " + std::to_string(i / 3) + " lies beyond +/-1e12";
  }
  if (!normals_.empty() && normals_.size() != 3 * n) return "normals do not match the vertices";
  if (!uv_.empty() && uv_.size() != 2 * n) return "uv do not match the vertices";
  for (float v : normals_)
    if (!std::isfinite(v)) return "a vertex normal is not finite";
  for (float v : uv_)
    if (!std::isfinite(v)) return "a vertex uv is not finite";
  bool someArea = false;
  for (size_t t = 0; t < triangleCount(); ++t) {
    const uint32_t* i = triangle(t);
    for (int k = 0; k < 3; ++k)
      if (i[k] >= n)
        return "triangle " + std::to_string(t) + " refers to vertex " + std::to_string(i[k]) +
               " of " + std::to_string(n);
    if (!someArea) {
      const TriangleShape c = corners(t);
      someArea = length(cross(c.b - c.a, c.c - c.a)) > 0;
    }
  }
  if (!someArea) return "every triangle has zero area";
  return "";
}

size_t TriangleMesh::zeroAreaTriangles() const {
  size_t flat = 0;
  for (size_t t = 0; t < triangleCount(); ++t) {
    const TriangleShape c = corners(t);
    flat += !(length(cross(c.b - c.a, c.c - c.a)) > 0);
  }
  return flat;
}

} // namespace nx
