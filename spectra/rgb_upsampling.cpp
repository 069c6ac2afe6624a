#include "spectra/rgb_upsampling.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/matrix3.h"
#include "spectra/illuminants.h"

namespace nx {
namespace {

// D65-weighted colour matching functions at 1 nm, normalised so a white reflector has Y = 1.
struct WeightedCmf {
  std::vector<double> x, y, z;
  Xyz white;
};

const WeightedCmf& weightedCmf() {
  static const WeightedCmf w = [] {
    const Spectrum d65 = illuminantD(nominalDaylightCct(65));
    const auto& t = cieTables();
    WeightedCmf r;
    double norm = 0;
    for (int i = 0; i < kCieSamples; ++i) norm += d65(kCieMinNm + i) * t.yBar[i];
    for (int i = 0; i < kCieSamples; ++i) {
      const double e = d65(kCieMinNm + i) / norm;
      r.x.push_back(e * t.xBar[i]);
      r.y.push_back(e * t.yBar[i]);
      r.z.push_back(e * t.zBar[i]);
      r.white.x += r.x.back();
      r.white.y += r.y.back();
      r.white.z += r.z.back();
    }
    return r;
  }();
  return w;
}

using Coeffs = Vector3d;

Lab labOf(const Coeffs& c) {
  const auto& w = weightedCmf();
  const SigmoidPolynomialSpectrum s{c[0], c[1], c[2]};
  Xyz xyz;
  for (int i = 0; i < kCieSamples; ++i) {
    const double v = s(kCieMinNm + i);
    xyz.x += v * w.x[i];
    xyz.y += v * w.y[i];
    xyz.z += v * w.z[i];
  }
  return xyzToLab(xyz, w.white);
}

Vector3d residual(const Coeffs& c, const Lab& target) {
  const Lab l = labOf(c);
  return {l.l - target.l, l.a - target.a, l.b - target.b};
}

double norm2(const Vector3d& v) {
  return v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
}

// Levenberg-Marquardt on the three coefficients; returns the best coefficients found.
Coeffs solve(Coeffs c, const Lab& target) {
  Vector3d r = residual(c, target);
  double mu = 1e-3;
  for (int iter = 0; iter < 200 && norm2(r) > 1e-10; ++iter) {
    Matrix3 j{};
    for (int k = 0; k < 3; ++k) {
      Coeffs cp = c;
      const double h = 1e-6 * std::max(1.0, std::abs(c[k]));
      cp[k] += h;
      const Vector3d rp = residual(cp, target);
      for (int row = 0; row < 3; ++row) j[row][k] = (rp[row] - r[row]) / h;
    }
    Matrix3 jtj{};
    Vector3d jtr{};
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b)
        for (int row = 0; row < 3; ++row) jtj[a][b] += j[row][a] * j[row][b];
      for (int row = 0; row < 3; ++row) jtr[a] += j[row][a] * r[row];
    }
    bool improved = false;
    for (int attempt = 0; attempt < 12 && !improved; ++attempt) {
      Matrix3 damped = jtj;
      for (int a = 0; a < 3; ++a) damped[a][a] += mu * std::max(jtj[a][a], 1e-12);
      if (std::abs(determinant(damped)) < 1e-300) {
        mu *= 10;
        continue;
      }
      const Vector3d step = multiply(inverse(damped), jtr);
      const Coeffs trial{c[0] - step[0], c[1] - step[1], c[2] - step[2]};
      const Vector3d rt = residual(trial, target);
      if (std::isfinite(norm2(rt)) && norm2(rt) < norm2(r)) {
        c = trial;
        r = rt;
        mu = std::max(mu * 0.3, 1e-9);
        improved = true;
      } else {
        mu *= 10;
      }
    }
    if (!improved) break;
  }
  return c;
}

} // namespace

Spectrum upsampleSrgbReflectance(const Rgb& rgb) {
  for (double v : {rgb.r, rgb.g, rgb.b})
    if (!(v >= 0.0 && v <= 1.0))
      throw Error("reflectance colour channels must lie in [0, 1], found " + std::to_string(v));
  if (rgb.r == rgb.g && rgb.g == rgb.b && (rgb.r == 0.0 || rgb.r == 1.0))
    return Spectrum(ConstantSpectrum{rgb.r});
  const auto& w = weightedCmf();
  const int steps = 8;
  Coeffs c{0, 0, 0}; // s = 1/2 everywhere: mid grey
  for (int k = 1; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    const Rgb mid{0.5 + (rgb.r - 0.5) * t, 0.5 + (rgb.g - 0.5) * t, 0.5 + (rgb.b - 0.5) * t};
    const Xyz target = linearSrgbToXyz(mid);
    const Xyz scaled{target.x * w.white.y, target.y * w.white.y, target.z * w.white.y};
    c = solve(c, xyzToLab(scaled, w.white));
  }
  return Spectrum(SigmoidPolynomialSpectrum{c[0], c[1], c[2]});
}

Spectrum upsampleSrgbIlluminant(const Rgb& rgb) {
  for (double v : {rgb.r, rgb.g, rgb.b})
    if (!(v >= 0.0 && std::isfinite(v)))
      throw Error("emission colour channels must be finite and non-negative, found " +
                  std::to_string(v));
  const double m = std::max({rgb.r, rgb.g, rgb.b});
  if (m == 0) return Spectrum(ConstantSpectrum{0});
  const Spectrum shape = upsampleSrgbReflectance({rgb.r / m, rgb.g / m, rgb.b / m});
  const Spectrum d65 = *namedEmission("D65");
  std::vector<double> nm, v;
  for (int l = 300; l <= 830; ++l) {
    nm.push_back(l);
    v.push_back(m * shape(l) * d65(l));
  }
  return Spectrum(TabulatedSpectrum{std::move(nm), std::move(v)});
}

Rgb reflectanceToLinearSrgb(const Spectrum& reflectance) {
  static const Spectrum d65 = illuminantD(nominalDaylightCct(65));
  return xyzToLinearSrgb(reflectanceToXyz(reflectance, d65));
}

} // namespace nx
