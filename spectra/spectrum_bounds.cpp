#include "spectra/spectrum_bounds.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace nx {
namespace {

// Accumulates candidate (wavelength, value) points of a spectrum's kind.
struct Extremes {
  SpectrumExtremes e{INFINITY, 0, -INFINITY, 0};
  bool bad = false;
  void add(double nm, double v) {
    if (!std::isfinite(v)) bad = true;
    if (v < e.min) e.min = v, e.minNm = nm;
    if (v > e.max) e.max = v, e.maxNm = nm;
  }
};

// Piecewise-linear data between knots (nm[i], value(i)) and, outside [nm.front(), nm.back()],
// zero or (holdEnds) the end values: the extremes lie at knots inside the interval or at its
// ends.
template <typename Knots, typename Value, typename At>
void addPiecewiseLinear(Extremes& x, const Knots& nm, const Value& value, double lo, double hi,
                        const At& at, bool holdEnds) {
  x.add(lo, at(lo));
  x.add(hi, at(hi));
  const auto first = std::lower_bound(nm.begin(), nm.end(), lo);
  for (auto it = first; it != nm.end() && *it <= hi; ++it)
    x.add(*it, value(static_cast<size_t>(it - nm.begin())));
  if (!holdEnds && (lo < nm.front() || hi > nm.back())) x.add(lo < nm.front() ? lo : hi, 0.0);
}

// Maximum of a smooth function by sampling every `step` nm, refined by golden-section search
// around the best sample.
template <typename F>
void addSampledMaximum(Extremes& x, const F& f, double lo, double hi, double step) {
  const int n = std::max(2, static_cast<int>(std::ceil((hi - lo) / step)));
  double best = lo, bestValue = -INFINITY;
  for (int i = 0; i <= n; ++i) {
    const double nm = lo + (hi - lo) * i / n;
    const double v = f(nm);
    x.add(nm, v);
    if (v > bestValue) bestValue = v, best = nm;
  }
  double a = std::max(lo, best - (hi - lo) / n), b = std::min(hi, best + (hi - lo) / n);
  const double r = 0.5 * (std::sqrt(5.0) - 1);
  while (b - a > 1e-6) {
    const double c = b - r * (b - a), d = a + r * (b - a);
    if (f(c) > f(d))
      b = d;
    else
      a = c;
  }
  x.add(0.5 * (a + b), f(0.5 * (a + b)));
}

} // namespace

double spectrumMean(const Spectrum& s, double loNm, double hiNm) {
  std::vector<double> at{loNm, hiNm};
  // The knots inside, and the points just beyond a table's ends (a table that is zero beyond
  // them steps there).
  const auto knots = [&](const auto& nm, bool holdEnds) {
    for (double x : nm)
      if (x > loNm && x < hiNm) at.push_back(x);
    if (!holdEnds && !nm.empty())
      for (double edge :
           {std::nextafter(nm.front(), -INFINITY), std::nextafter(nm.back(), INFINITY)})
        if (edge > loNm && edge < hiNm) at.push_back(edge);
  };
  if (const auto* t = std::get_if<TabulatedSpectrum>(&s.kind())) {
    knots(t->nm, t->holdEnds);
  } else if (const auto* d = std::get_if<DenseSpectrum>(&s.kind())) {
    std::vector<double> nm;
    for (size_t i = 0; i < d->value.size(); ++i)
      nm.push_back(DenseSpectrum::startNm + DenseSpectrum::stepNm * static_cast<double>(i));
    knots(nm, true);
  } else if (!std::holds_alternative<ConstantSpectrum>(s.kind())) {
    const int n = std::max(1, static_cast<int>(std::ceil((hiNm - loNm) / 0.05)));
    for (int i = 1; i < n; ++i) at.push_back(loNm + (hiNm - loNm) * i / n);
  }
  std::sort(at.begin(), at.end());
  double sum = 0, previous = s(at[0]);
  for (size_t i = 1; i < at.size(); ++i) {
    const double v = s(at[i]);
    sum += 0.5 * (previous + v) * (at[i] - at[i - 1]);
    previous = v;
  }
  return sum / (hiNm - loNm);
}

SpectrumExtremes spectrumExtremes(const Spectrum& s, double lo, double hi) {
  Extremes x;
  std::visit(
      [&](const auto& k) {
        using K = std::decay_t<decltype(k)>;
        if constexpr (std::is_same_v<K, ConstantSpectrum>) {
          x.add(lo, k.value);
        } else if constexpr (std::is_same_v<K, TabulatedSpectrum>) {
          addPiecewiseLinear(
              x, k.nm, [&](size_t i) { return k.value[i]; }, lo, hi, k, k.holdEnds);
        } else if constexpr (std::is_same_v<K, DenseSpectrum>) {
          std::vector<double> knots(k.value.size());
          for (size_t i = 0; i < knots.size(); ++i)
            knots[i] = K::startNm + K::stepNm * static_cast<double>(i);
          addPiecewiseLinear(
              x, knots, [&](size_t i) { return static_cast<double>(k.value[i]); }, lo, hi, k,
              false);
        } else if constexpr (std::is_same_v<K, GaussianSpectrum>) {
          // Unimodal around the mean; never below its ends' values.
          x.add(lo, k(lo));
          x.add(hi, k(hi));
          const double peak = std::clamp(k.meanNm, lo, hi);
          x.add(peak, k(peak));
        } else if constexpr (std::is_same_v<K, BlackbodySpectrum>) {
          // Unimodal with its peak at Wien's displacement wavelength (b = 2.897771955e6 nm K).
          x.add(lo, k(lo));
          x.add(hi, k(hi));
          const double peak = std::clamp(2.897771955e6 / k.kelvin, lo, hi);
          x.add(peak, k(peak));
        } else if constexpr (std::is_same_v<K, SigmoidPolynomialSpectrum>) {
          // Increasing in the quadratic p(x): its extremes at the ends or its vertex.
          x.add(lo, k(lo));
          x.add(hi, k(hi));
          if (k.c0 != 0) {
            const double vertex = 360.0 + 470.0 * (-k.c1 / (2 * k.c0));
            if (vertex > lo && vertex < hi) x.add(vertex, k(vertex));
          }
        } else {
          // Skew-Cauchy: a Cauchy density times a sigmoid in (0, 1), never negative.
          addSampledMaximum(x, k, lo, hi, std::max(1e-3, std::min(0.1, k.widthNm / 50)));
        }
      },
      s.kind());
  SpectrumExtremes e = x.e;
  const double scale = s.scale();
  e.min *= scale, e.max *= scale;
  if (scale < 0) std::swap(e.min, e.max), std::swap(e.minNm, e.maxNm);
  if (x.bad || !std::isfinite(scale)) e.min = e.max = NAN;
  return e;
}

std::string emissionProblem(const Spectrum& s) {
  const SpectrumExtremes e = spectrumExtremes(s, kTraceMinNm, kTraceMaxNm);
  if (e.min >= 0 && e.max <= kMaxEmission) return "";
  const bool low = !(e.min >= 0);
  return "expected an emission within [0, " + numberText(kMaxEmission) +
         "] (W m^-2 sr^-1 nm^-1; W sr^-1 nm^-1 for point lights) at every wavelength of " +
         numberText(kTraceMinNm) + "-" + numberText(kTraceMaxNm) + " nm, found " +
         (std::isnan(e.min) ? std::string("a non-finite value")
                            : numberText(low ? e.min : e.max) + " at " +
                                  numberText(low ? e.minNm : e.maxNm) + " nm");
}

} // namespace nx
