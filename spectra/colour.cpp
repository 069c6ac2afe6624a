#include "spectra/colour.h"

#include <cmath>

#include "core/math_util.h"
#include "core/matrix3.h"

namespace nx {

Xyz spectrumToXyz(const Spectrum& s) {
  const auto& t = cieTables();
  Xyz c;
  for (int i = 0; i < kCieSamples; ++i) {
    const double v = s(kCieMinNm + i);
    c.x += v * t.xBar[i];
    c.y += v * t.yBar[i];
    c.z += v * t.zBar[i];
  }
  return {c.x / kCieYIntegral, c.y / kCieYIntegral, c.z / kCieYIntegral};
}

Xyz reflectanceToXyz(const Spectrum& reflectance, const Spectrum& illuminant) {
  const auto& t = cieTables();
  Xyz c;
  double norm = 0;
  for (int i = 0; i < kCieSamples; ++i) {
    const double e = illuminant(kCieMinNm + i);
    const double v = reflectance(kCieMinNm + i) * e;
    c.x += v * t.xBar[i];
    c.y += v * t.yBar[i];
    c.z += v * t.zBar[i];
    norm += e * t.yBar[i];
  }
  return {c.x / norm, c.y / norm, c.z / norm};
}

namespace {

std::array<double, 3> apply(const Matrix3& m, double x, double y, double z) {
  return multiply(m, {x, y, z});
}

const Matrix3& srgbToXyz() {
  static const Matrix3 m = rgbToXyzMatrix({0.64, 0.33, 0.30, 0.60, 0.15, 0.06, 0.3127, 0.3290});
  return m;
}

const Matrix3& xyzToSrgb() {
  static const Matrix3 m = inverse(srgbToXyz());
  return m;
}

} // namespace

Matrix3 rgbToXyzMatrix(const std::array<double, 8>& xy) {
  // Columns: XYZ of each primary with Y = 1, then scaled so that RGB (1,1,1) maps to the white.
  Matrix3 p{};
  for (int k = 0; k < 3; ++k) {
    const double x = xy[2 * k], y = xy[2 * k + 1];
    p[0][k] = x / y;
    p[1][k] = 1.0;
    p[2][k] = (1.0 - x - y) / y;
  }
  const double wx = xy[6], wy = xy[7];
  const auto s = apply(inverse(p), wx / wy, 1.0, (1.0 - wx - wy) / wy);
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) p[r][k] *= s[k];
  return p;
}

Rgb xyzToLinearSrgb(const Xyz& c) {
  const auto v = apply(xyzToSrgb(), c.x, c.y, c.z);
  return {v[0], v[1], v[2]};
}

Xyz linearSrgbToXyz(const Rgb& c) {
  const auto v = apply(srgbToXyz(), c.r, c.g, c.b);
  return {v[0], v[1], v[2]};
}

double srgbEncode(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

double srgbDecode(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

Xyz d65WhiteXyz() {
  return {0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290};
}

Lab xyzToLab(const Xyz& c, const Xyz& white) {
  auto f = [](double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
  };
  const double fx = f(c.x / white.x), fy = f(c.y / white.y), fz = f(c.z / white.z);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double deltaE2000(const Lab& p, const Lab& q) {
  const double deg = kPi / 180.0;
  const double c1 = std::hypot(p.a, p.b), c2 = std::hypot(q.a, q.b);
  const double cBar7 = std::pow(0.5 * (c1 + c2), 7.0);
  const double g = 0.5 * (1.0 - std::sqrt(cBar7 / (cBar7 + std::pow(25.0, 7.0))));
  const double a1 = (1.0 + g) * p.a, a2 = (1.0 + g) * q.a;
  const double cp1 = std::hypot(a1, p.b), cp2 = std::hypot(a2, q.b);
  auto hue = [&](double b, double a) {
    if (a == 0.0 && b == 0.0) return 0.0;
    double h = std::atan2(b, a) / deg;
    return h < 0 ? h + 360.0 : h;
  };
  const double h1 = hue(p.b, a1), h2 = hue(q.b, a2);
  const double dL = q.l - p.l, dC = cp2 - cp1;
  double dh = 0;
  if (cp1 * cp2 != 0.0) {
    dh = h2 - h1;
    if (dh > 180.0)
      dh -= 360.0;
    else if (dh < -180.0)
      dh += 360.0;
  }
  const double dH = 2.0 * std::sqrt(cp1 * cp2) * std::sin(0.5 * dh * deg);
  const double lBar = 0.5 * (p.l + q.l), cBar = 0.5 * (cp1 + cp2);
  double hBar = h1 + h2;
  if (cp1 * cp2 != 0.0) {
    if (std::abs(h1 - h2) <= 180.0)
      hBar *= 0.5;
    else
      hBar = (h1 + h2 < 360.0) ? 0.5 * (h1 + h2 + 360.0) : 0.5 * (h1 + h2 - 360.0);
  }
  const double t = 1.0 - 0.17 * std::cos((hBar - 30.0) * deg) + 0.24 * std::cos(2 * hBar * deg) +
                   0.32 * std::cos((3 * hBar + 6.0) * deg) -
                   0.20 * std::cos((4 * hBar - 63.0) * deg);
  const double dTheta = 30.0 * std::exp(-sqr((hBar - 275.0) / 25.0));
  const double cBarP7 = std::pow(cBar, 7.0);
  const double rc = 2.0 * std::sqrt(cBarP7 / (cBarP7 + std::pow(25.0, 7.0)));
  const double sl = 1.0 + 0.015 * sqr(lBar - 50.0) / std::sqrt(20.0 + sqr(lBar - 50.0));
  const double sc = 1.0 + 0.045 * cBar;
  const double sh = 1.0 + 0.015 * cBar * t;
  const double rt = -std::sin(2.0 * dTheta * deg) * rc;
  return std::sqrt(sqr(dL / sl) + sqr(dC / sc) + sqr(dH / sh) + rt * (dC / sc) * (dH / sh));
}

} // namespace nx
