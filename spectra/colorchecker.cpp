#include "spectra/colorchecker.h"

#include "core/text_table.h"

namespace nx {

extern const char* const kColorCheckerCsv;

namespace {

struct Chart {
  std::vector<std::string> names;
  std::vector<Spectrum> patches;
};

const Chart& chart() {
  static const Chart c = [] {
    const NumberTable t = parseNumberTable(kColorCheckerCsv, "colorchecker_ohta.csv", true);
    Chart r;
    for (size_t col = 1; col < t.header.size(); ++col) {
      std::vector<double> nm, v;
      for (const auto& row : t.rows) {
        nm.push_back(row.values[0]);
        v.push_back(row.values[col]);
      }
      r.names.push_back(t.header[col]);
      r.patches.emplace_back(TabulatedSpectrum{std::move(nm), std::move(v)});
    }
    return r;
  }();
  return c;
}

} // namespace

const std::vector<std::string>& colorCheckerPatchNames() {
  return chart().names;
}

const Spectrum& colorCheckerPatch(int index) {
  return chart().patches[static_cast<size_t>(index)];
}

std::optional<Spectrum> colorCheckerPatch(const std::string& name) {
  const Chart& c = chart();
  for (size_t i = 0; i < c.names.size(); ++i)
    if (c.names[i] == name) return c.patches[i];
  return std::nullopt;
}

} // namespace nx
