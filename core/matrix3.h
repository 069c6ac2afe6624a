#pragma once
// Small dense 3x3 matrices in double precision (colour spaces, tiny least-squares solves).

#include <array>

namespace nx {

/// A 3x3 row-major matrix.
using Matrix3 = std::array<std::array<double, 3>, 3>;
/// A 3-vector of doubles.
using Vector3d = std::array<double, 3>;

/// m * v.
inline Vector3d multiply(const Matrix3& m, const Vector3d& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
          m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

/// Determinant of m.
inline double determinant(const Matrix3& m) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/// Inverse of m by the adjugate (m must be non-singular).
inline Matrix3 inverse(const Matrix3& m) {
  const double a = m[0][0], b = m[0][1], c = m[0][2];
  const double d = m[1][0], e = m[1][1], f = m[1][2];
  const double g = m[2][0], h = m[2][1], i = m[2][2];
  const double det = determinant(m);
  return {{{(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det},
           {(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det},
           {(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det}}};
}

} // namespace nx
