#include "spectra/cie.h"
#include "core/cell_index.h"

#include <cmath>

#include "core/error.h"
#include "core/text_table.h"

namespace nx {

extern const char* const kCie1931Csv;

const CieTables& cieTables() {
  static const CieTables tables = [] {
    const NumberTable t = parseNumberTable(kCie1931Csv, "cie1931_2deg_1nm.csv", true);
    if (t.rows.size() != kCieSamples) throw Error("cie1931_2deg_1nm.csv: wrong row count");
    CieTables r{};
    for (size_t i = 0; i < t.rows.size(); ++i) {
      const auto& v = t.rows[i].values;
      if (v.size() != 4 || v[0] != kCieMinNm + static_cast<double>(i))
        throw Error("cie1931_2deg_1nm.csv: malformed row " + std::to_string(t.rows[i].line));
      r.xBar[i] = v[1];
      r.yBar[i] = v[2];
      r.zBar[i] = v[3];
    }
    return r;
  }();
  return tables;
}

Xyz cieCmf(double nm) {
  if (!(nm >= kCieMinNm && nm <= kCieMaxNm)) return {};
  const auto& t = cieTables();
  const double x = nm - kCieMinNm;
  const int i = cellIndex(x, kCieSamples - 1);
  const double f = x - i;
  auto at = [&](const std::array<double, kCieSamples>& a) { return a[i] + (a[i + 1] - a[i]) * f; };
  return {at(t.xBar), at(t.yBar), at(t.zBar)};
}

} // namespace nx
