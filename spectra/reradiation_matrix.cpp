#include "spectra/reradiation_matrix.h"

#include "spectra/eem_import.h"
#include "spectra/spectrum_bounds.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "core/error.h"
#include "core/file_text.h"
#include "core/hash.h"
#include "core/text_table.h"

namespace nx {

uint64_t measuredMatrixDigest(const MeasuredMatrix& m) {
  uint64_t h = fnv1a64("");
  for (const std::vector<double>* v : {&m.excitationNm, &m.emissionNm, &m.cells})
    h = fnv1a64(
        std::string_view(reinterpret_cast<const char*>(v->data()), v->size() * sizeof(double)),
        fnv1a64(std::to_string(v->size()), h));
  return h;
}

ExcitationGuide excitationGuideOf(const Spectrum* s) {
  using RM = ReradiationMatrix;
  ExcitationGuide g;
  if (!s) {
    g.mean.fill(1.0f);
    return g;
  }
  constexpr int kSteps = 20;
  g.lo = RM::kBins, g.hi = 0;
  for (int i = 0; i < RM::kBins; ++i) {
    double sum = 0;
    for (int j = 0; j < kSteps; ++j)
      sum += std::max(0.0, (*s)(RM::kMinNm + (i + (j + 0.5) / kSteps) * RM::kBinNm));
    g.mean[static_cast<size_t>(i)] = static_cast<float>(sum / kSteps);
    if (sum > 0) g.lo = std::min(g.lo, i), g.hi = i + 1;
  }
  if (g.hi <= g.lo) g.lo = g.hi = 0;
  return g;
}

ReradiationMatrix ReradiationMatrix::fromModel(const FluorescenceModel& p) {
  const SkewCauchySpectrum absorption{p.absorptionPeakNm, p.widthNm, -p.skew};
  const SkewCauchySpectrum emission{p.absorptionPeakNm + p.stokesNm, p.widthNm, p.skew};
  std::array<double, kBins> a{}, e{};
  double aMax = 0;
  for (int i = 0; i < kBins; ++i) {
    a[i] = absorption(centre(i));
    aMax = std::max(aMax, a[i]);
    e[i] = emission(centre(i));
  }
  for (double& x : a) x = aMax > 0 ? p.peakAbsorptance * x / aMax : 0.0;
  if (!(std::accumulate(e.begin(), e.end(), 0.0) > 0)) return fromSpectra(a, {}, 0.0);
  return fromSpectra(a, e, p.quantumYield);
}

ReradiationMatrix ReradiationMatrix::fromSpectra(const std::array<double, kBins>& absorptance,
                                                 const std::array<double, kBins>& emission,
                                                 double quantumYield) {
  ReradiationMatrix r;
  const double eSum = std::accumulate(emission.begin(), emission.end(), 0.0);
  if (!(eSum > 0) && quantumYield > 0)
    throw Error("expected an emission spectrum above 0 somewhere in " +
                std::to_string(int(kMinNm)) + "-" + std::to_string(int(kMaxNm)) +
                " nm, found 0 everywhere");
  for (int i = 0; i < kBins; ++i) r.absorptance_[i] = absorptance[i];
  for (int i = 0; i < kBins; ++i)
    for (int o = i + 1; o < kBins; ++o) // e_o / eSum: the integral of e over bin o
      r.m_[static_cast<size_t>(i) * kBins + o] =
          absorptance[i] * quantumYield * (emission[o] / eSum) * centre(i) / centre(o);
  r.finish();
  return r;
}

ReradiationMatrix separableMatrix(const Spectrum& absorptance, const Spectrum& emission,
                                  double quantumYield, bool normaliseAbsorptance,
                                  const std::string& where, std::string* warning) {
  using R = ReradiationMatrix;
  const std::string range = numberText(R::kMinNm) + "-" + numberText(R::kMaxNm) + " nm";
  // Checked at every wavelength of the grid's range, not only at the bins' centres (an
  // absorptance of 1.7 between two centres was accepted).
  const SpectrumExtremes ax = spectrumExtremes(absorptance, R::kMinNm, R::kMaxNm);
  if (!(ax.min >= 0))
    throw Error(where + ": expected an absorptance of at least 0, found " + numberText(ax.min) +
                " at " + numberText(ax.minNm) + " nm");
  if (!normaliseAbsorptance && !(ax.max <= 1))
    throw Error(where + ": expected an absorptance within [0, 1], found " + numberText(ax.max) +
                " at " + numberText(ax.maxNm) + " nm");
  const SpectrumExtremes ex = spectrumExtremes(emission, R::kMinNm, R::kMaxNm);
  if (!(ex.min >= 0))
    throw Error(where + ": expected an emission spectrum of at least 0, found " +
                numberText(ex.min) + " at " + numberText(ex.minNm) + " nm");
  // Each bin takes the spectra's mean over it: a line narrower than a bin, or between two
  // centres, counts with its integral (sampled at the centres it was "0 everywhere").
  std::array<double, R::kBins> a{}, e{};
  double aMax = 0, eSum = 0;
  for (int i = 0; i < R::kBins; ++i) {
    const double lo = R::kMinNm + i * R::kBinNm, hi = lo + R::kBinNm;
    a[i] = spectrumMean(absorptance, lo, hi);
    e[i] = spectrumMean(emission, lo, hi);
    aMax = std::max(aMax, a[i]);
    eSum += e[i];
  }
  if (!(eSum > 0))
    throw Error(where + ": expected an emission spectrum above 0 somewhere in " + range +
                ", found 0 everywhere");
  if (normaliseAbsorptance) {
    if (!(aMax > 0))
      throw Error(where + ": expected an absorptance above 0 somewhere in " + range +
                  ", found 0 everywhere");
    for (double& x : a) x /= aMax;
  }
  // The share of the absorbed light's emission the matrix models: emission at longer
  // wavelengths than the absorption (Stokes), for light absorbed in proportion to the
  // absorptance. The rule of the EEM import: refused below 1%, warned below 50%.
  std::array<double, R::kBins + 1> above{}; // emission in the bins above each (summed from the
  for (int i = R::kBins - 1; i >= 0; --i)   // top: no cancellation)
    above[i] = above[i + 1] + (i + 1 < R::kBins ? e[i + 1] : 0.0);
  double absorbed = 0, modelled = 0;
  for (int i = 0; i < R::kBins; ++i) {
    absorbed += a[i];
    modelled += a[i] * above[i] / eSum;
  }
  if (absorbed > 0 && quantumYield > 0) {
    const double share = modelled / absorbed;
    const std::string found =
        numberText(100 * share) + "% of its emission at longer wavelengths than what it absorbs";
    if (share < kEemMinModelledFraction)
      throw Error(where +
                  ": expected a dye that emits at longer wavelengths than it absorbs "
                  "(the matrix models Stokes-shifted light only), found " +
                  found + " (an emission below the absorption renders no fluorescence)");
    if (share < kEemWarnModelledFraction && warning)
      *warning = where +
                 ": warning: the dye's emission is mostly at or below its absorption: " + found +
                 " is rendered (the rest of its light is missing)";
  }
  return R::fromSpectra(a, e, quantumYield);
}

namespace {

// Linear interpolation weights of x in an increasing grid; false outside it.
bool bracket(const std::vector<double>& g, double x, size_t& k, double& t) {
  if (g.empty() || x < g.front() || x > g.back()) return false;
  k = static_cast<size_t>(std::upper_bound(g.begin(), g.end(), x) - g.begin());
  k = k == 0 ? 0 : k - 1;
  if (k + 1 >= g.size()) {
    k = g.size() >= 2 ? g.size() - 2 : 0;
    t = g.size() >= 2 ? 1.0 : 0.0;
    return true;
  }
  t = (x - g[k]) / (g[k + 1] - g[k]);
  return true;
}

} // namespace

std::vector<double> gridCellWidths(const std::vector<double>& nm) {
  const size_t n = nm.size();
  std::vector<double> width(n);
  for (size_t c = 0; c < n; ++c) {
    const double lo = nm[c > 0 ? c - 1 : c], hi = nm[c + 1 < n ? c + 1 : c];
    width[c] = (hi - lo) / static_cast<double>((c > 0 ? 1 : 0) + (c + 1 < n ? 1 : 0));
  }
  return width;
}

std::vector<double> emittedPhotonsPerBin(const ReradiationMatrix& m) {
  std::vector<double> out(ReradiationMatrix::kBins, 0.0);
  for (int o = 0; o < ReradiationMatrix::kBins; ++o)
    for (int i = 0; i < o; ++i)
      out[static_cast<size_t>(o)] +=
          m(i, o) * ReradiationMatrix::centre(o) / ReradiationMatrix::centre(i);
  return out;
}

uint32_t MeasuredResampling::diagonal(int o) {
  constexpr int n = ReradiationMatrix::kBins;
  return static_cast<uint32_t>(n * n + o);
}

MeasuredResampling measuredResampling(const MeasuredMatrix& mm) {
  using R = ReradiationMatrix;
  constexpr int n = R::kBins;
  MeasuredResampling map;
  const size_t nEm = mm.emissionNm.size();
  // Emission bin widths of the CSV grid (to turn fractions per CSV bin into densities per nm).
  const std::vector<double> width = gridCellWidths(mm.emissionNm);
  auto add = [&](size_t row, size_t col, uint32_t output, double w) {
    // Off-diagonal density: cells with emission longer than excitation; the rest count as 0.
    if (w != 0 && mm.emissionNm[col] > mm.excitationNm[row])
      map.terms.push_back(
          {static_cast<uint32_t>(row * nEm + col), output, w * R::kBinNm / width[col]});
  };
  for (int i = 0; i < n; ++i) {
    size_t ri;
    double ti;
    if (!bracket(mm.excitationNm, R::centre(i), ri, ti)) continue;
    for (int o = i + 1; o < n; ++o) {
      size_t co;
      double to;
      if (!bracket(mm.emissionNm, R::centre(o), co, to)) continue;
      const auto out = static_cast<uint32_t>(i * n + o);
      add(ri, co, out, (1 - ti) * (1 - to));
      add(ri, co + 1, out, (1 - ti) * to);
      add(ri + 1, co, out, ti * (1 - to));
      add(ri + 1, co + 1, out, ti * to);
    }
  }
  // Diagonal: the reflectance where excitation and emission wavelengths coincide.
  std::vector<double> diagNm;
  std::vector<uint32_t> diagCell;
  for (size_t row = 0; row < mm.excitationNm.size(); ++row)
    for (size_t col = 0; col < nEm; ++col)
      if (std::abs(mm.excitationNm[row] - mm.emissionNm[col]) < 1e-9) {
        diagNm.push_back(mm.emissionNm[col]);
        diagCell.push_back(static_cast<uint32_t>(row * nEm + col));
      }
  for (int o = 0; o < n && diagNm.size() >= 2; ++o) {
    size_t k;
    double t;
    if (!bracket(diagNm, R::centre(o), k, t)) continue;
    if (t != 1) map.terms.push_back({diagCell[k], MeasuredResampling::diagonal(o), 1 - t});
    if (t != 0) map.terms.push_back({diagCell[k + 1], MeasuredResampling::diagonal(o), t});
  }
  return map;
}

ReradiationMatrix ReradiationMatrix::fromMeasured(const MeasuredMatrix& mm, const Spectrum* rho) {
  ReradiationMatrix r;
  r.measured_ = true;
  const size_t nEx = mm.excitationNm.size(), nEm = mm.emissionNm.size();
  // The diagonal's cells (where excitation and emission wavelengths coincide).
  bool zeroDiagonal = true;
  size_t diagonalCells = 0;
  for (size_t row = 0; row < nEx; ++row)
    for (size_t col = 0; col < nEm; ++col)
      if (std::abs(mm.excitationNm[row] - mm.emissionNm[col]) < 1e-9) {
        ++diagonalCells;
        zeroDiagonal = zeroDiagonal && mm.cells[row * nEm + col] == 0;
      }
  // A diagonal of zeros is a fluorescence-only measurement written as a full matrix: like a
  // missing one, the elastic part is the surface's reflectance (else it reflected nothing and
  // its <reflectance> was ignored without a word).
  r.zeroDiagonal_ = diagonalCells >= 2 && zeroDiagonal;
  r.elasticFromRho_ = mm.fluorescenceOnly || diagonalCells < 2 || r.zeroDiagonal_;
  const uint32_t firstDiagonal = MeasuredResampling::diagonal(0);
  for (const MeasuredResampling::Term& t : measuredResampling(mm).terms) {
    const double v = t.w * mm.cells[t.input];
    if (t.output < firstDiagonal)
      r.m_[t.output] += v;
    else if (!r.elasticFromRho_)
      r.diagonal_[t.output - firstDiagonal] += v;
  }
  r.finish();
  // Energy: light arriving at excitation bin i is reflected elastically (the diagonal D(i)) or
  // absorbed, and re-radiated at most in full: D(i) + sum_o M[i][o] <= 1 (a measured matrix
  // with 0.9 on its diagonal and 0.79 re-radiated had an albedo of 1.69).
  for (int i = 0; i < kBins; ++i) {
    double out = 0;
    for (int o = 0; o < kBins; ++o) out += r(i, o);
    const double elastic = r.elasticFromRho_ ? (rho ? (*rho)(centre(i)) : 0.0) : r.diagonal_[i];
    if (elastic + out > 1.0 + 1e-9)
      throw Error(
          mm.source + ": expected a matrix whose reflectance (" +
          (r.elasticFromRho_
               ? (r.zeroDiagonal_ ? "the surface's <reflectance>: the matrix's diagonal is all zero"
                                  : "the surface's <reflectance>: the matrix has no diagonal")
               : "diagonal") +
          ") plus re-radiated energy is at most 1 at every excitation wavelength, found " +
          numberText(elastic + out) + " at " + numberText(centre(i)) + " nm (reflectance " +
          numberText(elastic) + ", re-radiated " + numberText(out) + ")");
  }
  return r;
}

double ReradiationMatrix::guideMismatch(const ExcitationGuide& guide, int o) const {
  // Weights v(e) of the column's events and the guide's value g(e) at each.
  double total = elastic(o, 1.0), first = total * guide.mean[static_cast<size_t>(o)];
  double second = first * guide.mean[static_cast<size_t>(o)];
  for (int i = 0; i < o; ++i) {
    const double v = (*this)(i, o), g = guide.mean[static_cast<size_t>(i)];
    total += v;
    first += v * g;
    second += v * g * g;
  }
  if (!(total > 0) || !(first > 0)) return 1;
  return second * total / (first * first);
}

void ReradiationMatrix::finish() {
  cdf_.assign(static_cast<size_t>(kBins) * kBins, 0.0f);
  for (int o = 0; o < kBins; ++o) {
    double sum = 0;
    for (int i = 0; i < kBins; ++i) {
      sum += (*this)(i, o);
      cdf_[static_cast<size_t>(o) * kBins + i] = static_cast<float>(sum);
    }
    columnSum_[o] = sum;
  }
  guide_.assign(static_cast<size_t>(kBins) * kGuide, 0);
  for (int o = 0; o < kBins; ++o) {
    ColumnSampling& col = columns_[o];
    col.elasticScale = elasticFromRho_ ? 1.0f
                       : measured_     ? 0.0f
                                       : static_cast<float>(1 - absorptance_[o]);
    col.elasticConstant = measured_ && !elasticFromRho_ ? static_cast<float>(diagonal_[o]) : 0.0f;
    col.sum = static_cast<float>(columnSum_[o]);
    col.guideScale = col.sum > 0 ? static_cast<float>(kGuide) / col.sum : 0.0f;
    const float* cdf = &cdf_[static_cast<size_t>(o) * kBins];
    for (int j = 0; j < kGuide && col.sum > 0; ++j) {
      const float start = col.sum * static_cast<float>(j) / static_cast<float>(kGuide);
      const int i = static_cast<int>(std::upper_bound(cdf, cdf + kBins, start) - cdf);
      guide_[static_cast<size_t>(o) * kGuide + j] = static_cast<uint8_t>(std::min(i, kBins - 1));
    }
  }
}

std::string ReradiationMatrix::toCsv() const {
  std::ostringstream out;
  out.precision(17);
  out << "excitation/emission";
  for (int o = 0; o < kBins; ++o) out << "," << centre(o);
  out << "\n";
  for (int i = 0; i < kBins; ++i) {
    out << centre(i);
    for (int o = 0; o < kBins; ++o) out << "," << (o == i ? elastic(i, 1.0) : (*this)(i, o));
    out << "\n";
  }
  return out.str();
}

MeasuredMatrix readMeasuredMatrixCsv(const std::string& path) {
  return parseMeasuredMatrixCsv(readRegularFile(path, 64u << 20, "table file"), path);
}

MeasuredMatrix parseMeasuredMatrixCsv(const std::string& text, const std::string& source) {
  return parseWavelengthGrid(text, source, true, "excitation", "emission");
}

MeasuredMatrix parseWavelengthGrid(const std::string& text, const std::string& source,
                                   bool fractions, const std::string& rowAxis,
                                   const std::string& columnAxis, double bytesPerCell) {
  const NumberTable t = parseNumberTable(text, source, true, bytesPerCell);
  const std::string& path = source;
  MeasuredMatrix m;
  m.source = path;
  size_t firstRow = 0;
  if (!t.header.empty()) {
    for (size_t i = 1; i < t.header.size(); ++i)
      m.emissionNm.push_back(
          parseNumber(t.header[i], path + ":1", "an " + columnAxis + " wavelength"));
  } else {
    m.emissionNm.assign(t.rows[0].values.begin() + 1, t.rows[0].values.end());
    firstRow = 1;
  }
  if (m.emissionNm.size() < 2)
    throw Error(path + ":1: expected at least two " + columnAxis + " wavelengths in the first row");
  for (size_t i = 1; i < m.emissionNm.size(); ++i)
    if (!(m.emissionNm[i] > m.emissionNm[i - 1]))
      throw Error(path + ":1: expected increasing " + columnAxis + " wavelengths, found " +
                  std::to_string(m.emissionNm[i]) + " after " +
                  std::to_string(m.emissionNm[i - 1]));
  for (size_t r = firstRow; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    const std::string where = path + ":" + std::to_string(row.line);
    if (row.values.size() != m.emissionNm.size() + 1)
      throw Error(where + ": expected " + std::to_string(m.emissionNm.size() + 1) + " cells (" +
                  rowAxis + " wavelength and " + std::to_string(m.emissionNm.size()) +
                  " values), found " + std::to_string(row.values.size()));
    if (!m.excitationNm.empty() && !(row.values[0] > m.excitationNm.back()))
      throw Error(where + ": expected increasing " + rowAxis + " wavelengths, found " +
                  std::to_string(row.values[0]) + " after " +
                  std::to_string(m.excitationNm.back()));
    for (size_t k = 1; fractions && k < row.values.size(); ++k)
      if (row.values[k] < 0 || row.values[k] > 1)
        throw Error(where + ": expected matrix values in [0, 1], found " +
                    std::to_string(row.values[k]));
    m.excitationNm.push_back(row.values[0]);
    m.cells.insert(m.cells.end(), row.values.begin() + 1, row.values.end());
  }
  if (m.excitationNm.size() < 2) throw Error(path + ": expected at least two " + rowAxis + " rows");
  return m;
}

void checkMeasuredMatrix(const MeasuredMatrix& m, const std::string& where) {
  for (const auto& [axis, nm] :
       {std::pair{"excitation", &m.excitationNm}, std::pair{"emission", &m.emissionNm}}) {
    if (nm->size() < 2)
      throw Error(where + ": expected at least two " + axis + " wavelengths, found " +
                  std::to_string(nm->size()));
    for (size_t i = 0; i < nm->size(); ++i) {
      if (!((*nm)[i] >= 100 && (*nm)[i] <= 2000))
        throw Error(where + ": expected " + axis + " wavelengths in nm within [100, 2000], found " +
                    std::to_string((*nm)[i]));
      if (i > 0 && !((*nm)[i] > (*nm)[i - 1]))
        throw Error(where + ": expected increasing " + axis + " wavelengths, found " +
                    std::to_string((*nm)[i]) + " after " + std::to_string((*nm)[i - 1]));
    }
  }
  if (m.cells.size() != m.excitationNm.size() * m.emissionNm.size())
    throw Error(where + ": expected " + std::to_string(m.excitationNm.size()) + " x " +
                std::to_string(m.emissionNm.size()) + " cells (excitation x emission), found " +
                std::to_string(m.cells.size()));
  for (double v : m.cells)
    if (!(v >= 0 && v <= 1))
      throw Error(where + ": expected matrix values in [0, 1], found " + std::to_string(v));
}

} // namespace nx
