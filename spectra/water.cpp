#include "spectra/water.h"

#include "core/text_table.h"

namespace nx {

extern const char* const kWaterCsv;

namespace {

// Column `col` of the table as a spectrum held constant beyond its ends.
Spectrum waterColumn(size_t col) {
  const NumberTable t = parseNumberTable(kWaterCsv, "water_smith_baker_1981.csv", true);
  TabulatedSpectrum s;
  for (const auto& row : t.rows) {
    s.nm.push_back(row.values[0]);
    s.value.push_back(row.values[col]);
  }
  s.holdEnds = true;
  return Spectrum(std::move(s));
}

} // namespace

std::optional<Spectrum> namedMediumCoefficient(const std::string& name) {
  static const Spectrum absorption = waterColumn(1), scattering = waterColumn(2);
  if (name == "water:absorption") return absorption;
  if (name == "water:scattering") return scattering;
  return std::nullopt;
}

} // namespace nx
