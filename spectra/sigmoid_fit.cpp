#include "spectra/sigmoid_fit.h"

#include <algorithm>
#include <cmath>
#include <vector>

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

Lab labOf(const SigmoidCoefficients& c) {
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

// CIELAB of a linear sRGB colour as a reflectance under D65 (white maps to the D65 white).
Lab targetLab(const Rgb& rgb) {
  const auto& w = weightedCmf();
  const Xyz target = linearSrgbToXyz(rgb);
  const Xyz scaled{target.x * w.white.y, target.y * w.white.y, target.z * w.white.y};
  return xyzToLab(scaled, w.white);
}

// XYZ of the coefficients' spectrum and its derivatives d XYZ / d c_k, in one pass over the
// 1 nm samples: S(p) = 1/2 + p / (2 sqrt(1 + p^2)), S'(p) = 1 / (2 (1 + p^2)^(3/2)), and
// p = c0 x^2 + c1 x + c2 with x the wavelength normalised as in SigmoidPolynomialSpectrum.
struct XyzWithJacobian {
  Xyz xyz;
  Matrix3 d{}; // d[row][k]: row X, Y, Z; k the coefficient
};

XyzWithJacobian xyzWithJacobian(const SigmoidCoefficients& c) {
  const auto& w = weightedCmf();
  XyzWithJacobian r;
  for (int i = 0; i < kCieSamples; ++i) {
    const double x = (kCieMinNm + i - kSigmoidStartNm) / kSigmoidSpanNm;
    const double p = (c[0] * x + c[1]) * x + c[2];
    const double q = 1.0 / std::sqrt(1.0 + p * p);
    const double v = 0.5 + 0.5 * p * q, dv = 0.5 * q * q * q;
    const double basis[3] = {x * x, x, 1.0};
    const double cmf[3] = {w.x[i], w.y[i], w.z[i]};
    r.xyz.x += v * cmf[0];
    r.xyz.y += v * cmf[1];
    r.xyz.z += v * cmf[2];
    for (int row = 0; row < 3; ++row)
      for (int k = 0; k < 3; ++k) r.d[row][k] += dv * basis[k] * cmf[row];
  }
  return r;
}

Vector3d labResidual(const Xyz& xyz, const Lab& target) {
  const Lab l = xyzToLab(xyz, weightedCmf().white);
  return {l.l - target.l, l.a - target.a, l.b - target.b};
}

double norm2(const Vector3d& v) {
  return v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
}

// Levenberg-Marquardt on the three coefficients; returns the best coefficients found. The
// Jacobian is d Lab / d XYZ (by differences of the cheap XYZ -> Lab map) times the analytic
// d XYZ / d c.
SigmoidCoefficients solve(SigmoidCoefficients c, const Lab& target) {
  XyzWithJacobian e = xyzWithJacobian(c);
  Vector3d r = labResidual(e.xyz, target);
  double mu = 1e-3;
  for (int iter = 0; iter < 200 && norm2(r) > 1e-10; ++iter) {
    Matrix3 j{};
    for (int k = 0; k < 3; ++k) {
      const double scale =
          std::max({std::abs(e.d[0][k]), std::abs(e.d[1][k]), std::abs(e.d[2][k])});
      const double h = scale > 0 ? 1e-7 / scale : 1.0;
      const Xyz moved{e.xyz.x + h * e.d[0][k], e.xyz.y + h * e.d[1][k], e.xyz.z + h * e.d[2][k]};
      const Vector3d rp = labResidual(moved, target);
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
      const SigmoidCoefficients trial{c[0] - step[0], c[1] - step[1], c[2] - step[2]};
      const XyzWithJacobian et = xyzWithJacobian(trial);
      const Vector3d rt = labResidual(et.xyz, target);
      if (std::isfinite(norm2(rt)) && norm2(rt) < norm2(r)) {
        c = trial;
        e = et;
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

SigmoidCoefficients greySigmoidCoefficients(double z) {
  // S(p) = 1/2 + p / (2 sqrt(1 + p^2)) = z  <=>  p = s / sqrt(1 - s^2) with s = 2z - 1.
  const double s = 2.0 * z - 1.0;
  return {0.0, 0.0, s / std::sqrt(1.0 - s * s)};
}

SigmoidCoefficients fitSigmoidCoefficients(const Rgb& rgb, SigmoidCoefficients start) {
  return solve(start, targetLab(rgb));
}

SigmoidCoefficients fitSigmoidCoefficientsFrom(const Rgb& rgb, const Rgb& from,
                                               SigmoidCoefficients c, int steps) {
  for (int k = 1; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    const Rgb mid{from.r + (rgb.r - from.r) * t, from.g + (rgb.g - from.g) * t,
                  from.b + (rgb.b - from.b) * t};
    c = solve(c, targetLab(mid));
  }
  return c;
}

double sigmoidFitDeltaE(const SigmoidCoefficients& c, const Rgb& rgb) {
  return deltaE2000(labOf(c), targetLab(rgb));
}

} // namespace nx
