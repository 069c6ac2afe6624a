#pragma once
// Closed forms of the fluorescent furnace (a camera inside a closed sphere of one fluorescent
// material emitting a flat Le), computed on the re-radiation matrix's grid, independently of
// the renderer.

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "spectra/reradiation_matrix.h"
#include "spectra/sensor.h"

namespace nx::test {

/// Solves A x = b by Gaussian elimination with partial pivoting.
inline std::vector<double> solveLinear(std::vector<std::vector<double>> a, std::vector<double> b) {
  const size_t n = b.size();
  for (size_t c = 0; c < n; ++c) {
    size_t p = c;
    for (size_t r = c + 1; r < n; ++r)
      if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
    std::swap(a[c], a[p]);
    std::swap(b[c], b[p]);
    for (size_t r = c + 1; r < n; ++r) {
      const double f = a[r][c] / a[c][c];
      for (size_t k = c; k < n; ++k) a[r][k] -= f * a[c][k];
      b[r] -= f * b[c];
    }
  }
  std::vector<double> x(n);
  for (size_t r = n; r-- > 0;) {
    double s = b[r];
    for (size_t k = r + 1; k < n; ++k) s -= a[r][k] * x[k];
    x[r] = s / a[r][r];
  }
  return x;
}

/// The furnace's radiance per 5 nm bin for an emission with bin means le: L = (I - diag(D) -
/// M^T)^-1 Le, D the elastic part for reflectance rho.
inline std::vector<double> furnaceRadiance(const ReradiationMatrix& m, double rho,
                                           std::vector<double> le) {
  using RM = ReradiationMatrix;
  std::vector<std::vector<double>> a(RM::kBins, std::vector<double>(RM::kBins, 0));
  for (int o = 0; o < RM::kBins; ++o) {
    a[o][o] = 1 - m.elastic(o, rho);
    for (int i = 0; i < RM::kBins; ++i) a[o][i] -= m(i, o); // (M^T)[o][i]
  }
  return solveLinear(a, std::move(le));
}

/// The same for a flat emission le.
inline std::vector<double> furnaceRadiance(const ReradiationMatrix& m, double rho, double le) {
  return furnaceRadiance(m, rho, std::vector<double>(ReradiationMatrix::kBins, le));
}

/// Bin means of a spectrum on the matrix's 5 nm grid (midpoint rule, 1000 points per bin).
inline std::vector<double> binMeans(const std::function<double(double)>& spectrum) {
  using RM = ReradiationMatrix;
  std::vector<double> means(RM::kBins, 0);
  for (int o = 0; o < RM::kBins; ++o) {
    const int n = 1000;
    for (int j = 0; j < n; ++j) means[o] += spectrum(RM::kMinNm + (o + (j + 0.5) / n) * RM::kBinNm);
    means[o] /= n;
  }
  return means;
}

/// Bands of 10 nm starting on the grid cover two 5 nm bins each: their average.
inline double bandOfBins(const std::vector<double>& perBin, const Sensor& bands, int b) {
  const int first = ReradiationMatrix::binOf(bands.channel(b).lo + 0.1);
  return 0.5 * (perBin[static_cast<size_t>(first)] + perBin[static_cast<size_t>(first) + 1]);
}

/// A royal-blue LED's spectrum as a scene text: a Gaussian at 450 nm of FWHM 20 nm sampled every
/// 2 nm over 420-480 nm (zero outside), and the same function for the closed forms.
inline std::string royalBlueLedText() {
  std::string text;
  for (int nm = 420; nm <= 480; nm += 2)
    text += (text.empty() ? "" : ", ") + std::to_string(nm) + ":" +
            std::to_string(std::exp(-0.5 * std::pow((nm - 450) / (20 / 2.35482), 2)));
  return text;
}

/// The spectrum royalBlueLedText() describes, interpolated as the scene reader does.
inline double royalBlueLed(double nm) {
  if (nm < 420 || nm > 480) return 0;
  const double lo = 420 + 2 * std::floor((nm - 420) / 2), hi = std::min(lo + 2, 480.0);
  const auto at = [](double x) {
    return std::stod(std::to_string(std::exp(-0.5 * std::pow((x - 450) / (20 / 2.35482), 2))));
  };
  if (hi == lo) return at(lo);
  return at(lo) + (at(hi) - at(lo)) * (nm - lo) / (hi - lo);
}

} // namespace nx::test
