#include "integrators/ior_model.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace nx {

bool namedGlass(const char* name, IorModel& out) {
  using K = IorModel::Kind;
  if (std::strcmp(name, "bk7") == 0) {
    out = {K::Sellmeier,
           {1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653}};
    return true;
  }
  if (std::strcmp(name, "diamond") == 0) {
    out = {K::Sellmeier, {0.3306, 4.3356, 0.0, 0.1750 * 0.1750, 0.1060 * 0.1060, 0.0}};
    return true;
  }
  if (std::strcmp(name, "fused_silica") == 0) {
    out = {K::Sellmeier,
           {0.6961663, 0.4079426, 0.8974794, 0.0684043 * 0.0684043, 0.1162414 * 0.1162414,
            9.896161 * 9.896161}};
    return true;
  }
  return false;
}

namespace {

// One Sellmeier term B s / (s - C) at s = l^2 (um^2).
double sellmeierTerm(double b, double c, double s) {
  return b * s / (s - c);
}

// Sellmeier: n^2 - 1 = sum of terms over s in [sLo, sHi] (no pole inside) against
// [gMin, gMax] = [nMin^2 - 1, nMax^2 - 1]: returns an s where it falls outside, or a negative
// value. Each term is monotone in s, so the sum of the terms' smaller (larger) end values
// bounds the sum below (above) on an interval; undecided intervals are halved.
double sellmeierOutside(const IorModel& m, double sLo, double sHi, double gMin, double gMax) {
  struct Span {
    double a, b;
    int depth;
  };
  std::vector<Span> stack{{sLo, sHi, 0}};
  int budget = 1 << 18; // spans; only an index hugging a limit over a long range gets near it
  auto g = [&](double s) {
    double sum = 0;
    for (int i = 0; i < 3; ++i) sum += sellmeierTerm(m.c[i], m.c[i + 3], s);
    return sum;
  };
  while (!stack.empty() && --budget > 0) {
    const Span sp = stack.back();
    stack.pop_back();
    double lower = 0, upper = 0;
    for (int i = 0; i < 3; ++i) {
      const double ta = sellmeierTerm(m.c[i], m.c[i + 3], sp.a),
                   tb = sellmeierTerm(m.c[i], m.c[i + 3], sp.b);
      lower += std::min(ta, tb);
      upper += std::max(ta, tb);
    }
    if (lower >= gMin && upper <= gMax) continue;
    for (double s : {sp.a, sp.b, 0.5 * (sp.a + sp.b)}) {
      const double v = g(s);
      if (!(v >= gMin && v <= gMax)) return s;
    }
    // Bounds converge to the values as the span shrinks; at 2^-50 of the range the remaining
    // gap is rounding.
    if (sp.depth < 50) {
      const double mid = 0.5 * (sp.a + sp.b);
      stack.push_back({sp.a, mid, sp.depth + 1});
      stack.push_back({mid, sp.b, sp.depth + 1});
    }
  }
  return -1;
}

} // namespace

std::optional<double> iorOutsideRange(const IorModel& m, double loNm, double hiNm, double nMin,
                                      double nMax) {
  auto outside = [&](double n) { return !(std::isfinite(n) && n >= nMin && n <= nMax); };
  switch (m.kind) {
  case IorModel::Kind::Constant:
    if (outside(m.c[0])) return loNm;
    return std::nullopt;
  case IorModel::Kind::Cauchy: {
    // n = A + B x + C x^2 with x = 1 / l^2 (l in um).
    const double xLo = 1e6 / (hiNm * hiNm), xHi = 1e6 / (loNm * loNm);
    std::vector<double> xs{xLo, xHi};
    if (m.c[2] != 0) {
      const double vertex = -m.c[1] / (2 * m.c[2]);
      if (vertex > xLo && vertex < xHi) xs.push_back(vertex);
    }
    for (double x : xs)
      if (outside(m.c[0] + m.c[1] * x + m.c[2] * x * x)) return 1e3 / std::sqrt(x);
    return std::nullopt;
  }
  case IorModel::Kind::Sellmeier: {
    const double sLo = loNm * loNm * 1e-6, sHi = hiNm * hiNm * 1e-6;
    for (int i = 0; i < 3; ++i)
      if (m.c[i] != 0 && m.c[i + 3] >= sLo && m.c[i + 3] <= sHi)
        return std::sqrt(m.c[i + 3]) * 1e3; // a pole
    const double s = sellmeierOutside(m, sLo, sHi, nMin * nMin - 1, nMax * nMax - 1);
    if (s >= 0) return std::sqrt(s) * 1e3;
    return std::nullopt;
  }
  }
  return loNm;
}

} // namespace nx
