#pragma once
// Three-component vectors used for points, directions and normals (float and double).

#include <algorithm>
#include <cmath>

namespace nx {

/// A 3D vector (points, directions and normals alike).
template <typename T>
struct Vec3T {
  T x = 0, y = 0, z = 0;

  constexpr Vec3T() = default;
  constexpr Vec3T(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
  /// Conversion between precisions (explicit: narrowing must be visible).
  template <typename U>
  constexpr explicit Vec3T(const Vec3T<U>& o)
      : x(static_cast<T>(o.x)), y(static_cast<T>(o.y)), z(static_cast<T>(o.z)) {}

  /// Component i (0 = x, 1 = y, 2 = z).
  constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3T operator-() const { return {-x, -y, -z}; }
  constexpr Vec3T& operator+=(const Vec3T& o) {
    x += o.x, y += o.y, z += o.z;
    return *this;
  }
  constexpr Vec3T& operator*=(T s) {
    x *= s, y *= s, z *= s;
    return *this;
  }
};

/// Single-precision vector: the renderer's working type.
using Vec3 = Vec3T<float>;
/// Double-precision vector: scene data and robust intersection.
using Vec3d = Vec3T<double>;

template <typename T>
constexpr Vec3T<T> operator+(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <typename T>
constexpr Vec3T<T> operator-(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename T>
constexpr Vec3T<T> operator*(const Vec3T<T>& a, T s) {
  return {a.x * s, a.y * s, a.z * s};
}
template <typename T>
constexpr Vec3T<T> operator*(T s, const Vec3T<T>& a) {
  return a * s;
}
template <typename T>
constexpr Vec3T<T> operator/(const Vec3T<T>& a, T s) {
  return a * (T(1) / s);
}
template <typename T>
constexpr bool operator==(const Vec3T<T>& a, const Vec3T<T>& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

/// Dot product.
template <typename T>
constexpr T dot(const Vec3T<T>& a, const Vec3T<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

/// Cross product (right-hand rule on the components).
template <typename T>
constexpr Vec3T<T> cross(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// Euclidean length.
template <typename T>
T length(const Vec3T<T>& a) {
  return std::sqrt(dot(a, a));
}

/// a scaled to unit length (a must not be zero).
template <typename T>
Vec3T<T> normalize(const Vec3T<T>& a) {
  return a / length(a);
}

/// a scaled to unit length for any non-zero a, however small or large (scaled by its largest
/// component first: the squares of 1e-300 underflow to 0). For inputs, not the render loop.
template <typename T>
Vec3T<T> normalizeAnyLength(const Vec3T<T>& a) {
  const T m = std::max(std::abs(a.x), std::max(std::abs(a.y), std::abs(a.z)));
  return normalize(a / m);
}

/// True when some component is not zero (a direction of any length).
template <typename T>
bool isNonZero(const Vec3T<T>& a) {
  return a.x != 0 || a.y != 0 || a.z != 0;
}

/// True when every component is finite.
template <typename T>
bool isFinite(const Vec3T<T>& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

} // namespace nx
