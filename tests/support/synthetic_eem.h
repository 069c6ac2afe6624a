#pragma once
// An instrument EEM synthesised from the skew-Cauchy fluorescence model (emission shape
// independent of excitation, counts in photons) with Rayleigh and water Raman lines: the
// input of the EEM import's closed-form tests.

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "core/params/eem_layout.h"
#include "spectra/reradiation_matrix.h"
#include "spectra/spectrum.h"

namespace nx::test {

/// A dye as the skew-Cauchy model: absorptance a_max f(ex; la, g, -w) / max, photon emission
/// density e(em) (per nm, integral 1 over [300, 1100) in bin steps).
struct Dye {
  double la = 460, stokes = 80, width = 20, skew = 10, yield = 0.6, aMax = 0.9;
  FluorescenceModel model() const { return {la, stokes, width, skew, yield, aMax}; }
  double absorptance(double nm) const {
    const SkewCauchySpectrum f{la, width, -skew};
    double peak = 0;
    for (int i = 0; i < ReradiationMatrix::kBins; ++i)
      peak = std::max(peak, f(ReradiationMatrix::centre(i)));
    return aMax * f(nm) / peak;
  }
  double emission(double nm) const {
    const SkewCauchySpectrum f{la + stokes, width, skew};
    double sum = 0;
    for (int i = 0; i < ReradiationMatrix::kBins; ++i)
      sum += f(ReradiationMatrix::centre(i)) * ReradiationMatrix::kBinNm;
    return f(nm) / sum;
  }
};

/// from, from + step, ... up to `to`.
inline std::vector<double> grid(double from, double to, double step) {
  std::vector<double> g;
  for (double x = from; x <= to + 1e-9; x += step) g.push_back(x);
  return g;
}

/// Counts of an instrument (scale k) for the dye, with Rayleigh lines (first and second order)
/// and water Raman, as a CSV in the given orientation.
struct Synthetic {
  std::vector<double> ex, em;
  double k = 5e4, rayleigh = 1e6, raman = 2e3;
  bool emissionRows = false, energy = false;
  double count(const Dye& d, double x, double m) const {
    auto line = [&](double centre, double sigma) {
      return std::exp(-0.5 * (m - centre) * (m - centre) / (sigma * sigma));
    };
    const double ramanNm = 1 / (1 / x - kWaterRamanShiftCm * 1e-7);
    // Lines of FWHM 2.4 nm (a 2.5 nm slit); removed with a 12 nm band, 0 outside it.
    double c = k * d.absorptance(x) * d.yield * d.emission(m) + rayleigh * line(x, 1) +
               0.05 * rayleigh * line(2 * x, 1) + raman * line(ramanNm, 1);
    return energy ? c / m : c; // energy per nm is photons / wavelength (up to a constant)
  }
  std::string csv(const Dye& d) const {
    std::ostringstream s;
    s.precision(10);
    const auto& rows = emissionRows ? em : ex;
    const auto& cols = emissionRows ? ex : em;
    s << (emissionRows ? "em\\ex" : "ex\\em");
    for (double c : cols) s << "," << c;
    s << "\n";
    for (double r : rows) {
      s << r;
      for (double c : cols) s << "," << (emissionRows ? count(d, c, r) : count(d, r, c));
      s << "\n";
    }
    return s.str();
  }
};

} // namespace nx::test
