#include "spectra/metals.h"

#include <array>
#include <complex>

#include "core/text_table.h"

namespace nx {

extern const char* const kMetalsCsv;

namespace {

constexpr double kEvNm = 1239.84193; // h c in eV nm

// Columns (n, k) of one metal in Johnson & Christy's table, as spectra over wavelength.
MetalIndex johnsonChristy(size_t nColumn) {
  const NumberTable t = parseNumberTable(kMetalsCsv, "metals_johnson_christy_1972.csv", true);
  TabulatedSpectrum n, k;
  for (auto row = t.rows.rbegin(); row != t.rows.rend(); ++row) { // rising wavelength
    const double nm = kEvNm / row->values[0];
    n.nm.push_back(nm);
    k.nm.push_back(nm);
    n.value.push_back(row->values[nColumn]);
    k.value.push_back(row->values[nColumn + 1]);
  }
  n.holdEnds = k.holdEnds = true;
  return {Spectrum(std::move(n)), Spectrum(std::move(k))};
}

MetalIndex aluminium() {
  TabulatedSpectrum n, k;
  n.holdEnds = k.holdEnds = true;
  for (double nm = 200; nm <= 2000; nm += 5) {
    double nv = 0, kv = 0;
    aluminiumIndex(nm, nv, kv);
    n.nm.push_back(nm);
    k.nm.push_back(nm);
    n.value.push_back(nv);
    k.value.push_back(kv);
  }
  return {Spectrum(std::move(n)), Spectrum(std::move(k))};
}

} // namespace

void aluminiumIndex(double nm, double& n, double& k) {
  // epsilon(w) = 1 - f0 wp^2 / (w (w + i G0)) + sum_j f_j wp^2 / (w_j^2 - w^2 - i w G_j),
  // energies in eV (Rakic et al. 1998, eqs. 1-3 and Table 1, Al).
  constexpr double wp = 14.98, f0 = 0.523, g0 = 0.047;
  constexpr std::array<std::array<double, 3>, 4> osc{{// f_j, G_j, w_j
                                                      {0.227, 0.333, 0.162},
                                                      {0.050, 0.312, 1.544},
                                                      {0.166, 1.351, 1.808},
                                                      {0.030, 3.382, 3.473}}};
  using C = std::complex<double>;
  const double w = kEvNm / nm;
  C eps = 1.0 - f0 * wp * wp / (w * C(w, g0));
  for (const auto& [f, g, wj] : osc) eps += f * wp * wp / C(wj * wj - w * w, -w * g);
  const C index = std::sqrt(eps); // principal root: k >= 0 as Im(eps) > 0
  n = index.real();
  k = index.imag();
}

const std::vector<std::string>& metalNames() {
  static const std::vector<std::string> names{"gold", "silver", "copper", "aluminium"};
  return names;
}

std::optional<MetalIndex> namedMetal(const std::string& name) {
  static const MetalIndex copper = johnsonChristy(1), silver = johnsonChristy(3),
                          gold = johnsonChristy(5), al = aluminium();
  if (name == "gold") return gold;
  if (name == "silver") return silver;
  if (name == "copper") return copper;
  if (name == "aluminium") return al;
  return std::nullopt;
}

} // namespace nx
