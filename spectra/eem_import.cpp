#include "spectra/eem_import.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"

namespace nx {

namespace {

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// S(row): the row's counts integrated over emission (cell widths of the grid).
std::vector<double> rowIntegrals(const EemTable& t, const std::vector<double>& width) {
  const size_t nEm = t.emissionNm.size();
  std::vector<double> s(t.excitationNm.size(), 0.0);
  for (size_t r = 0; r < s.size(); ++r)
    for (size_t c = 0; c < nEm; ++c) s[r] += t.counts[r * nEm + c] * width[c];
  return s;
}

// Linear interpolation of per-row values at excitation nm; nullopt outside the rows.
std::optional<double> atExcitation(const EemTable& t, const std::vector<double>& v, double nm) {
  const auto& g = t.excitationNm;
  if (nm < g.front() || nm > g.back()) return std::nullopt;
  size_t k = static_cast<size_t>(std::upper_bound(g.begin(), g.end(), nm) - g.begin());
  k = std::clamp<size_t>(k, 1, g.size() - 1) - 1;
  const double u = (nm - g[k]) / (g[k + 1] - g[k]);
  return (1 - u) * v[k] + u * v[k + 1];
}

// The rank-1 model s(row) p(col) of the counts fitted to the cells outside the bands by
// alternating least squares (Bro 1997); p integrates to 1 over emission. Columns with no cell
// outside a band take p linearly interpolated from their neighbours. Returns the fit's share
// of the counts explained, 1 - |residual|^2 / |counts|^2.
double rankOneFit(const EemTable& t, const std::vector<double>& width, std::vector<double>& s,
                  std::vector<double>& p) {
  const size_t nEx = t.excitationNm.size(), nEm = t.emissionNm.size();
  auto kept = [&](size_t r, size_t c) { return t.removed.empty() || !t.removed[r * nEm + c]; };
  s.assign(nEx, 1.0);
  p.assign(nEm, 0.0);
  for (size_t r = 0; r < nEx; ++r)
    for (size_t c = 0; c < nEm; ++c)
      if (kept(r, c)) p[c] += t.counts[r * nEm + c];
  std::vector<char> covered(nEm, 0);
  for (int iteration = 0; iteration < 50; ++iteration) {
    for (size_t r = 0; r < nEx; ++r) {
      double num = 0, den = 0;
      for (size_t c = 0; c < nEm; ++c)
        if (kept(r, c)) num += t.counts[r * nEm + c] * p[c], den += p[c] * p[c];
      s[r] = den > 0 ? num / den : 0.0;
    }
    for (size_t c = 0; c < nEm; ++c) {
      double num = 0, den = 0;
      for (size_t r = 0; r < nEx; ++r)
        if (kept(r, c)) num += t.counts[r * nEm + c] * s[r], den += s[r] * s[r];
      covered[c] = den > 0;
      p[c] = den > 0 ? num / den : 0.0;
    }
  }
  for (size_t c = 0; c < nEm; ++c) { // columns inside a band in every row
    if (covered[c]) continue;
    size_t lo = c, hi = c;
    while (lo > 0 && !covered[lo]) --lo;
    while (hi + 1 < nEm && !covered[hi]) ++hi;
    const double y0 = covered[lo] ? p[lo] : 0.0, y1 = covered[hi] ? p[hi] : 0.0;
    const double x0 = t.emissionNm[lo], x1 = t.emissionNm[hi];
    p[c] = x1 > x0 ? y0 + (y1 - y0) * (t.emissionNm[c] - x0) / (x1 - x0) : 0.0;
  }
  double integral = 0;
  for (size_t c = 0; c < nEm; ++c) integral += p[c] * width[c];
  if (!(integral > 0)) return 0.0;
  for (double& v : p) v /= integral;
  for (double& v : s) v *= integral;
  double residual = 0, total = 0;
  for (size_t r = 0; r < nEx; ++r)
    for (size_t c = 0; c < nEm; ++c)
      if (kept(r, c)) {
        const double v = t.counts[r * nEm + c];
        residual += (v - s[r] * p[c]) * (v - s[r] * p[c]);
        total += v * v;
      }
  return total > 0 ? 1 - residual / total : 0.0;
}

} // namespace

std::string EemSummary::text() const {
  std::ostringstream s;
  s << "quantum yield " << quantumYield << "; " << scatterCells
    << " cells inside Rayleigh/Raman bands interpolated over, " << negativeCells
    << " negative cells set to 0";
  if (meanShapeRows) s << ", " << meanShapeRows << " weak rows given the mean emission shape";
  if (meanShapeFit >= 0)
    s << "; one emission shape (Kasha's rule) explains " << num(100 * meanShapeFit)
      << "% of the counts outside the bands";
  s << "; " << coverageText();
  return s.str();
}

std::string EemSummary::coverageText() const {
  std::ostringstream s;
  s << num(100 * modelledFraction) << "% of the emitted photons modelled, "
    << num(100 * antiStokesFraction)
    << "% below their excitation wavelength (anti-Stokes, not modelled), "
    << num(100 * outsideGridFraction) << "% outside " << num(ReradiationMatrix::kMinNm) << "-"
    << num(ReradiationMatrix::kMaxNm) << " nm";
  return s.str();
}

EemTable parseEemCsv(const std::string& text, const std::string& source, const EemLayout& layout) {
  const char* rows = layout.emissionRows ? "emission" : "excitation";
  const char* cols = layout.emissionRows ? "excitation" : "emission";
  // Per cell beyond the table's own 8 bytes, at the import's peak: the grid (8), the counts
  // (8), the scatter-free copy and its flags (9), a rank-1 model (9) and the matrix (8).
  constexpr double kImportBytesPerCell = 42;
  const MeasuredMatrix g =
      parseWavelengthGrid(text, source, false, rows, cols, kImportBytesPerCell);
  EemTable t;
  t.source = source;
  const size_t nr = g.excitationNm.size(), nc = g.emissionNm.size();
  if (!layout.emissionRows) {
    t.excitationNm = g.excitationNm;
    t.emissionNm = g.emissionNm;
    t.counts = g.cells;
  } else {
    t.excitationNm = g.emissionNm;
    t.emissionNm = g.excitationNm;
    t.counts.resize(nr * nc);
    for (size_t r = 0; r < nr; ++r)
      for (size_t c = 0; c < nc; ++c) t.counts[c * nr + r] = g.cells[r * nc + c];
  }
  for (const auto& [axis, nm] :
       {std::pair{"excitation", &t.excitationNm}, std::pair{"emission", &t.emissionNm}})
    for (double x : *nm)
      if (!(x >= 100 && x <= 2000))
        throw Error(source + ": expected " + axis +
                    " wavelengths in nm within [100, 2000], found " + num(x) +
                    (layout.emissionRows ? " (layout=\"emission_rows\")" : ""));
  // Scale-free: counts near the float range's end (1e308) would overflow the row integrals,
  // subnormal ones (1e-318) lose digits; only their proportions matter.
  double largest = 0;
  for (double c : t.counts) largest = std::max(largest, std::abs(c));
  if (largest > 0) {
    t.scale = largest;
    for (double& c : t.counts) c /= largest;
  }
  return t;
}

EemTable withoutScatter(const EemTable& t, const EemLayout& layout, EemSummary& summary) {
  EemTable out = t;
  const size_t nEx = t.excitationNm.size(), nEm = t.emissionNm.size();
  out.removed.assign(nEx * nEm, 0);
  std::vector<char> band(nEm);
  for (size_t r = 0; r < nEx; ++r) {
    const double ex = t.excitationNm[r];
    double* row = &out.counts[r * nEm];
    std::vector<double> lines, halfWidths;
    if (layout.rayleighWidthNm > 0) {
      lines.push_back(ex);
      halfWidths.push_back(layout.rayleighWidthNm / 2);
      if (layout.secondOrder) {
        lines.push_back(2 * ex);
        halfWidths.push_back(layout.rayleighWidthNm / 2);
      }
    }
    // Raman: a fixed shift in wavenumber from the excitation, 1/em = 1/ex - shift (nm^-1).
    const double inverseRaman = 1.0 / ex - layout.ramanShiftCm * 1e-7;
    if (layout.ramanShiftCm > 0 && layout.ramanWidthNm > 0 && inverseRaman > 0) {
      lines.push_back(1.0 / inverseRaman);
      halfWidths.push_back(layout.ramanWidthNm / 2);
    }
    for (size_t c = 0; c < nEm; ++c) {
      const double em = t.emissionNm[c];
      if (layout.energyUnits) row[c] *= em; // energy per nm -> photons per nm (relative)
      band[c] = 0;
      for (size_t k = 0; k < lines.size(); ++k)
        if (std::abs(em - lines[k]) <= halfWidths[k]) band[c] = 1;
      out.removed[r * nEm + c] = band[c];
      if (band[c])
        ++summary.scatterCells;
      else if (row[c] < 0) {
        row[c] = 0;
        ++summary.negativeCells;
      }
    }
    // Each run of band cells: linear in wavelength between the cells either side of it.
    for (size_t a = 0; a < nEm;) {
      if (!band[a]) {
        ++a;
        continue;
      }
      size_t b = a;
      while (b + 1 < nEm && band[b + 1]) ++b;
      const bool hasLeft = a > 0, hasRight = b + 1 < nEm;
      const double x0 = hasLeft ? t.emissionNm[a - 1] : t.emissionNm[a];
      const double x1 = hasRight ? t.emissionNm[b + 1] : t.emissionNm[b];
      const double y0 = hasLeft ? row[a - 1] : 0.0, y1 = hasRight ? row[b + 1] : 0.0;
      for (size_t c = a; c <= b; ++c) {
        const double u = x1 > x0 ? (t.emissionNm[c] - x0) / (x1 - x0) : 0.0;
        row[c] = (1 - u) * y0 + u * y1;
      }
      a = b + 1;
    }
  }
  return out;
}

MeasuredMatrix donaldsonFromEem(const EemTable& clean, const EemLayout& layout,
                                const EemYield& yield, const EemAbsorptance& absorptance,
                                EemSummary& summary) {
  const size_t nEx = clean.excitationNm.size(), nEm = clean.emissionNm.size();
  const std::vector<double> width = gridCellWidths(clean.emissionNm);
  std::vector<double> s = rowIntegrals(clean, width);
  // Kasha's rule: the counts as the rank-1 model fitted outside the bands.
  std::optional<EemTable> modelled;
  if (layout.meanEmissionShape) {
    std::vector<double> shape;
    summary.meanShapeFit = rankOneFit(clean, width, s, shape);
    modelled = clean;
    for (size_t r = 0; r < nEx; ++r)
      for (size_t c = 0; c < nEm; ++c) modelled->counts[r * nEm + c] = s[r] * shape[c];
  }
  const EemTable& counts = modelled ? *modelled : clean;
  const double sMax = *std::max_element(s.begin(), s.end());
  if (!(sMax > 0))
    throw Error(clean.source + ": expected an EEM with emission left once its scatter bands are "
                               "removed, found none (every row integrates to 0)");
  auto sampleAbsorptance = [&](double nm, double rowIntegral) {
    return absorptance.spectrum ? absorptance.spectrum(nm) : *absorptance.peak * rowIntegral / sMax;
  };

  // The yield: given, or relative to a reference dye at one excitation wavelength,
  // Q = Q_R (S / A) / (S_R / A_R) (Lakowicz 2006, section 2.10; the same instrument, settings
  // and medium, so no refractive-index factor).
  double q = yield.quantumYield.value_or(0);
  if (yield.reference) {
    const EemTable& ref = *yield.reference;
    const std::vector<double> refWidth = gridCellWidths(ref.emissionNm);
    std::vector<double> sRef = rowIntegrals(ref, refWidth), unused;
    if (layout.meanEmissionShape) rankOneFit(ref, refWidth, sRef, unused);
    double nm = 0;
    if (yield.referenceExcitationNm)
      nm = *yield.referenceExcitationNm;
    else
      nm = ref.excitationNm[std::max_element(sRef.begin(), sRef.end()) - sRef.begin()];
    const auto sr = atExcitation(ref, sRef, nm);
    const auto ss = atExcitation(clean, s, nm);
    if (!sr || !ss)
      throw Error(clean.source + ": expected the reference excitation " + num(nm) +
                  " nm within both EEMs' excitation rows (" + num(clean.excitationNm.front()) +
                  "-" + num(clean.excitationNm.back()) + " nm and " +
                  num(ref.excitationNm.front()) + "-" + num(ref.excitationNm.back()) + " nm in " +
                  ref.source + "), found outside");
    const double a = sampleAbsorptance(nm, *ss);
    if (!(*sr > 0) || !(*ss > 0) || !(a > 0))
      throw Error(clean.source +
                  ": expected emission and absorptance at the reference excitation " + num(nm) +
                  " nm, found " +
                  (!(*sr > 0)   ? "no emission in the reference " + ref.source
                   : !(*ss > 0) ? std::string("no emission in the sample")
                                : std::string("an absorptance of 0")));
    // Both tables were divided by their own largest count: their ratio restores the scale
    // they share (an overflowing ratio gives an infinite yield, refused below).
    q = yield.referenceYield * (*ss / a) / (*sr / yield.referenceAbsorptance) *
        (clean.scale / ref.scale);
    // Below this, the sample's light is nothing beside the reference's: most likely the two
    // were not measured alike (a 1e308-count reference beside a plain sample).
    constexpr double kLeastYield = 1e-6;
    if (!(q >= kLeastYield))
      throw Error(clean.source + ": expected a quantum yield of at least " + num(kLeastYield) +
                  " from the reference dye " + ref.source + ", found " + num(q) +
                  " (the sample's emission is negligible beside the reference's: check that both "
                  "EEMs were measured with the same settings and in the same units)");
    if (!(q <= 1))
      throw Error(clean.source + ": expected a quantum yield at most 1 from the reference dye " +
                  ref.source + ", found " + num(q) +
                  " (check the reference's yield and absorptance, and that both EEMs were measured "
                  "with the same settings)");
  }
  summary.quantumYield = q;

  // The mean emission shape (Kasha's rule: one shape whatever the excitation).
  std::vector<double> meanShape(nEm, 0.0);
  double sSum = 0;
  for (size_t r = 0; r < nEx; ++r) {
    sSum += s[r];
    for (size_t c = 0; c < nEm; ++c) meanShape[c] += counts.counts[r * nEm + c];
  }
  for (double& v : meanShape) v /= sSum;

  MeasuredMatrix m;
  m.source = clean.source;
  m.fluorescenceOnly = true;
  m.excitationNm = clean.excitationNm;
  m.emissionNm = clean.emissionNm;
  m.cells.assign(nEx * nEm, 0.0);
  constexpr double kWeakRow = 1e-3; // a row below this share of the strongest: no own shape
  // The counts (photons) per nm of excitation (rows weighed by their excitation cells), sorted
  // by what the matrix makes of them.
  const std::vector<double> exWidth = gridCellWidths(clean.excitationNm);
  double emitted = 0, antiStokes = 0, outsideGrid = 0, kept = 0;
  for (size_t r = 0; r < nEx; ++r) {
    const double ex = clean.excitationNm[r];
    const bool ownShape = s[r] > kWeakRow * sMax;
    if (absorptance.spectrum && !ownShape && !layout.meanEmissionShape) ++summary.meanShapeRows;
    for (size_t c = 0; c < nEm; ++c) {
      double photons; // P(ex, em): photons per nm of emission per incident photon
      if (!absorptance.spectrum)
        photons = q * *absorptance.peak * counts.counts[r * nEm + c] / sMax;
      else
        photons = q * absorptance.spectrum(ex) *
                  (ownShape ? counts.counts[r * nEm + c] / s[r] : meanShape[c]);
      const double em = clean.emissionNm[c];
      // What the table describes, whatever the yield and absorptance (a yield of 0 is an
      // off switch, not an EEM that models nothing).
      const double share = counts.counts[r * nEm + c] * width[c] * exWidth[r];
      const int exBin = ReradiationMatrix::binOf(ex), emBin = ReradiationMatrix::binOf(em);
      if (em != ex) { // the elastic line (Rayleigh, when not removed) emits nothing
        emitted += share;
        if (em < ex)
          antiStokes += share;
        else if (exBin < 0 || emBin < 0)
          outsideGrid += share;
        else if (emBin > exBin)
          kept += share;
      }
      m.cells[r * nEm + c] = photons * width[c] * ex / em; // energy per cell
    }
  }
  summary.antiStokesFraction = emitted > 0 ? antiStokes / emitted : 0.0;
  summary.outsideGridFraction = emitted > 0 ? outsideGrid / emitted : 0.0;
  summary.modelledFraction = emitted > 0 ? kept / emitted : 0.0;
  // An EEM the matrix cannot model imports to (nearly) nothing: the render would equal the
  // plain surface's. Refused with what became of its photons.
  if (summary.modelledFraction < kEemMinModelledFraction)
    throw Error(clean.source + ": expected an EEM whose emission the matrix models (emission " +
                "longer than its excitation, both within " + num(ReradiationMatrix::kMinNm) + "-" +
                num(ReradiationMatrix::kMaxNm) + " nm), found " + summary.coverageText() +
                (summary.antiStokesFraction > 0.5
                     ? std::string(" (a transposed table? rows are excitation wavelengths unless "
                                   "layout=\"emission_rows\")")
                     : std::string()));
  return m;
}

} // namespace nx
