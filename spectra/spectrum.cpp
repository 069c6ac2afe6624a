#include "spectra/spectrum.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/math_util.h"
#include "core/text_table.h"

namespace nx {

double GaussianSpectrum::operator()(double nm) const {
  const double d = (nm - meanNm) / sigmaNm;
  return peak * std::exp(-0.5 * d * d);
}

double SkewCauchySpectrum::operator()(double nm) const {
  const double d = nm - locationNm;
  const double g = widthNm;
  return g / (kPi * (g * g + d * d)) * (std::atan(skew * d / g) * kInvPi + 0.5);
}

double BlackbodySpectrum::operator()(double nm) const {
  // CODATA 2018 exact SI constants.
  constexpr double h = 6.62607015e-34, c = 299792458.0, kB = 1.380649e-23;
  const double l = nm * 1e-9;
  const double perMetre =
      2.0 * h * c * c / (l * l * l * l * l) / std::expm1(h * c / (l * kB * kelvin));
  return perMetre * 1e-9; // per nanometre
}

double TabulatedSpectrum::operator()(double x) const {
  if (nm.empty()) return 0.0;
  if (x < nm.front()) return holdEnds ? value.front() : 0.0;
  if (x > nm.back()) return holdEnds ? value.back() : 0.0;
  size_t i;
  if (invStep > 0 && !std::isnan(x)) {
    // The interval nm[i] <= x < nm[i + 1] that the search below finds: the grid's guess is
    // within one interval of it (buildIndex), and one step each way settles it.
    const size_t last = nm.size() - 1;
    i = std::min(static_cast<size_t>((x - nm.front()) * invStep), last);
    if (i > 0 && x < nm[i]) --i;
    if (i < last && x >= nm[i + 1]) ++i;
    if (i == last) return value.back();
  } else if (!cellFirst.empty() && !std::isnan(x)) {
    // From the first interval of x's cell, forward past the wavelengths at or below x (a cell
    // is at least as wide as the closest two, so it holds few); back one where rounding put x
    // before its cell's start.
    const size_t last = nm.size() - 1;
    const size_t cell =
        std::min(static_cast<size_t>((x - nm.front()) * invCell), cellFirst.size() - 1);
    i = cellFirst[cell];
    while (i > 0 && x < nm[i]) --i;
    while (i < last && x >= nm[i + 1]) ++i;
    if (i == last) return value.back();
  } else {
    const auto it = std::upper_bound(nm.begin(), nm.end(), x);
    if (it == nm.end()) return value.back();
    i = static_cast<size_t>(it - nm.begin()) - 1;
  }
  const double t = (x - nm[i]) / (nm[i + 1] - nm[i]);
  return lerp(value[i], value[i + 1], t);
}

double SigmoidPolynomialSpectrum::operator()(double nm) const {
  const double x = (nm - kSigmoidStartNm) / kSigmoidSpanNm;
  const double p = (c0 * x + c1) * x + c2;
  if (std::isinf(p)) return p > 0 ? 1.0 : 0.0;
  return 0.5 + p / (2.0 * std::sqrt(1.0 + p * p));
}

void TabulatedSpectrum::buildIndex() {
  invStep = 0;
  invCell = 0;
  cellFirst.clear();
  if (nm.size() < 3) return; // a single interval: the search is one comparison
  const double range = nm.back() - nm.front();
  const double step = range / static_cast<double>(nm.size() - 1);
  bool even = true;
  double closest = range;
  for (size_t i = 0; i < nm.size(); ++i) {
    even = even && std::fabs(nm[i] - (nm.front() + step * static_cast<double>(i))) <= 0.5 * step;
    if (i > 0) closest = std::min(closest, nm[i] - nm[i - 1]);
  }
  if (even) {
    invStep = 1.0 / step;
    return;
  }
  const double width = std::max(closest, range / static_cast<double>(kIndexCells));
  const size_t cells = std::min(kIndexCells, static_cast<size_t>(std::ceil(range / width)));
  invCell = static_cast<double>(cells) / range;
  cellFirst.resize(cells);
  size_t i = 0;
  for (size_t c = 0; c < cells; ++c) {
    const double start = nm.front() + static_cast<double>(c) / invCell;
    while (i + 1 < nm.size() - 1 && nm[i + 1] <= start) ++i;
    cellFirst[c] = static_cast<uint32_t>(i);
  }
}

Spectrum forRendering(const Spectrum& s) {
  if (const auto* t = std::get_if<TabulatedSpectrum>(&s.kind())) {
    TabulatedSpectrum indexed = *t;
    indexed.buildIndex();
    return Spectrum(std::move(indexed), s.scale());
  }
  if (std::holds_alternative<ConstantSpectrum>(s.kind()) ||
      std::holds_alternative<DenseSpectrum>(s.kind()))
    return s;
  DenseSpectrum d;
  const int n = static_cast<int>((kTraceMaxNm - d.startNm) / d.stepNm) + 1;
  d.value.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) d.value.push_back(static_cast<float>(s(d.startNm + i * d.stepNm)));
  return Spectrum(std::move(d));
}

TabulatedSpectrum makeTabulated(std::vector<double> nm, std::vector<double> value,
                                const std::string& where) {
  if (nm.size() != value.size())
    throw Error(where + ": expected as many values as wavelengths, found " +
                std::to_string(nm.size()) + " wavelengths and " + std::to_string(value.size()) +
                " values");
  if (nm.size() < 2)
    throw Error(where + ": expected at least two (wavelength, value) pairs, found " +
                std::to_string(nm.size()));
  for (size_t i = 0; i < nm.size(); ++i) {
    if (!std::isfinite(nm[i]) || !std::isfinite(value[i]) || nm[i] <= 0)
      throw Error(where + ": expected finite values and positive wavelengths, found (" +
                  std::to_string(nm[i]) + ", " + std::to_string(value[i]) + ")");
    if (i > 0 && nm[i] <= nm[i - 1])
      throw Error(where + ": expected strictly increasing wavelengths, found " +
                  std::to_string(nm[i]) + " after " + std::to_string(nm[i - 1]));
  }
  return TabulatedSpectrum{std::move(nm), std::move(value)};
}

namespace {
// The header's names, for messages: "nm, a, b".
std::string headerList(const NumberTable& table) {
  std::string out;
  for (const std::string& h : table.header) out += (out.empty() ? "" : ", ") + h;
  return out;
}

// A tabulated spectrum from a parsed table: the wavelength column and the value column (the
// second, or the one the header names `column`). Errors name table.source and line.
TabulatedSpectrum spectrumFromTable(const NumberTable& table, const std::string& column) {
  const std::string& path = table.source;
  size_t valueColumn = 1, columns = 2;
  if (!column.empty()) {
    const auto it = std::find(table.header.begin(), table.header.end(), column);
    if (table.header.empty())
      throw Error(path + ":1: expected a header naming the columns (to find column '" + column +
                  "'), found none");
    if (it == table.header.begin() || it == table.header.end())
      throw Error(path + ":1: expected a value column named '" + column + "', found the columns " +
                  headerList(table));
    valueColumn = static_cast<size_t>(it - table.header.begin());
    columns = table.header.size();
  }
  std::vector<double> nm, value;
  for (const auto& row : table.rows) {
    const std::string where = path + ":" + std::to_string(row.line);
    if (row.values.size() != columns)
      throw Error(where + ": expected " + std::to_string(columns) +
                  (column.empty() ? " columns (wavelength, value)" : " columns (as the header)") +
                  ", found " + std::to_string(row.values.size()) +
                  (column.empty() && row.values.size() > 2 && table.header.size() > 2
                       ? " (choose one with column=\"name\": " + headerList(table) + ")"
                       : ""));
    if (!nm.empty() && row.values[0] <= nm.back())
      throw Error(where + ": expected wavelengths in increasing order, found " +
                  std::to_string(row.values[0]) + " after " + std::to_string(nm.back()));
    nm.push_back(row.values[0]);
    value.push_back(row.values[valueColumn]);
  }
  return makeTabulated(std::move(nm), std::move(value), path);
}
} // namespace

TabulatedSpectrum readSpectrumCsv(const std::string& path, const std::string& column) {
  return spectrumFromTable(readNumberTable(path, /*allowHeader=*/true), column);
}

TabulatedSpectrum parseSpectrumCsv(const std::string& text, const std::string& source,
                                   const std::string& column) {
  return spectrumFromTable(parseNumberTable(text, source, /*allowHeader=*/true), column);
}

} // namespace nx
