// EEM import against the closed form: an instrument EEM synthesised from the skew-Cauchy model
// (emission shape independent of excitation, counts in photons, Rayleigh and Raman lines
// added) must import to the model's Donaldson matrix.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "spectra/eem_import.h"
#include "support/errors.h"
#include "support/synthetic_eem.h"

namespace nx {
namespace {

using RM = ReradiationMatrix;
using test::Dye;
using test::grid;
using test::Synthetic;

// Excitation and emission at the matrix's bin centres (excitation up to 647.5 nm).
Synthetic onTheMatrixGrid() {
  Synthetic s;
  s.ex = grid(302.5, 647.5, 5);
  s.em = grid(302.5, 1097.5, 5);
  return s;
}

EemLayout scatterLayout(double width = 12, bool raman = true) {
  EemLayout l;
  l.rayleighWidthNm = width;
  l.ramanShiftCm = raman ? kWaterRamanShiftCm : 0;
  l.ramanWidthNm = raman ? 12 : 0;
  return l;
}

RM import(const std::string& csv, const EemLayout& l, const EemYield& y, const EemAbsorptance& a,
          EemSummary* out = nullptr) {
  EemSummary s;
  const EemTable clean = withoutScatter(parseEemCsv(csv, "dye.csv", l), l, s);
  const MeasuredMatrix m = donaldsonFromEem(clean, l, y, a, s);
  if (out) *out = s;
  EXPECT_TRUE(m.fluorescenceOnly);
  return RM::fromMeasured(m);
}

// f() must fail with a message containing `part`.
template <typename F>
void expectError(F&& f, const std::string& part) {
  const std::string m = test::errorMessage(f);
  EXPECT_NE(m.find(part), std::string::npos) << m;
}

EemYield given(double q) {
  EemYield y;
  y.quantumYield = q;
  return y;
}

EemAbsorptance peak(double aMax) {
  EemAbsorptance a;
  a.peak = aMax;
  return a;
}

// Largest |M - expected| over the cells with excitation bins in [from, to] nm, relative to
// the largest expected cell.
double worstError(const RM& got, const RM& want, double from, double to) {
  double worst = 0, scale = 0;
  for (int i = 0; i < RM::kBins; ++i)
    for (int o = 0; o < RM::kBins; ++o) scale = std::max(scale, want(i, o));
  for (int i = RM::binOf(from); i <= RM::binOf(to); ++i)
    for (int o = i + 1; o < RM::kBins; ++o)
      worst = std::max(worst, std::abs(got(i, o) - want(i, o)) / scale);
  return worst;
}

TEST(EemImport, OnTheMatrixGridItIsTheModelsMatrix) {
  // Excitation and emission at the bin centres over the whole grid: the import (scatter
  // removed, absorptance from the excitation profile) is the model's matrix but for the cells
  // inside the removed bands, which are interpolated.
  const Dye d;
  Synthetic s = onTheMatrixGrid();
  s.raman = 0; // a band over the emission peak: ABandOverTheEmissionPeak
  const RM want = RM::fromModel(d.model());
  EemSummary sum;
  const RM got = import(s.csv(d), scatterLayout(12, false), given(d.yield), peak(d.aMax), &sum);
  EXPECT_LT(worstError(got, want, 302.5, 647.5), 0.01);
  // Without removal the Rayleigh line is taken for fluorescence: the check can fail.
  EemLayout none;
  const RM raw = import(s.csv(d), none, given(d.yield), peak(d.aMax));
  EXPECT_GT(worstError(raw, want, 302.5, 647.5), 0.1);
  EXPECT_NEAR(sum.quantumYield, d.yield, 1e-12);
  EXPECT_GT(sum.scatterCells, s.ex.size() * 3);
  // Energy per excitation bin: the model's a Q sum e lambda_i / lambda_o, within 1%.
  for (int i = RM::binOf(400); i <= RM::binOf(520); ++i) {
    double g = 0, w = 0;
    for (int o = 0; o < RM::kBins; ++o) g += got(i, o), w += want(i, o);
    EXPECT_NEAR(g, w, 0.01 * w + 1e-6) << RM::centre(i);
  }
  EXPECT_TRUE(got.elasticFromReflectance());
  EXPECT_DOUBLE_EQ(got.elastic(RM::binOf(500), 0.86), 0.86);
}

TEST(EemImport, ABandOverTheEmissionPeak) {
  // Water Raman crosses this dye's emission peak (ex 450-460 nm: Raman at 530-540 nm).
  // Interpolating across it (emission_shape="rows") underestimates those rows, by 15% here;
  // the rank-1 fit outside the bands (emission_shape="mean") recovers the model.
  const Dye d;
  Synthetic s = onTheMatrixGrid();
  s.raman = 2e4;
  const RM want = RM::fromModel(d.model());
  EemLayout l = scatterLayout();
  const RM rows = import(s.csv(d), l, given(d.yield), peak(d.aMax));
  EXPECT_GT(worstError(rows, want, 302.5, 647.5), 0.05);
  l.meanEmissionShape = true;
  EemSummary sum;
  const RM mean = import(s.csv(d), l, given(d.yield), peak(d.aMax), &sum);
  EXPECT_LT(worstError(mean, want, 302.5, 647.5), 1e-3);
  EXPECT_GT(sum.meanShapeFit, 0.999);
  EXPECT_NE(sum.text().find("Kasha"), std::string::npos);
  // Two dyes with different emission shapes break Kasha's rule: the fit says so.
  Dye other;
  other.la = 380, other.stokes = 200;
  std::string csv = s.csv(d), csv2 = s.csv(other);
  const EemTable a = parseEemCsv(csv, "a.csv", l), b = parseEemCsv(csv2, "b.csv", l);
  EemTable both = a;
  for (size_t k = 0; k < both.counts.size(); ++k) both.counts[k] += b.counts[k];
  EemSummary mixed;
  donaldsonFromEem(withoutScatter(both, l, mixed), l, given(0.5), peak(0.5), mixed);
  EXPECT_LT(mixed.meanShapeFit, 0.98);
}

TEST(EemImport, InstrumentGridsWithAnEmissionWindow) {
  // The trial's grids: excitation 250-600 nm in 5 nm steps, emission 300-800 in 2 nm steps.
  // Expected: the model with its emission renormalised over the measured window (photons
  // beyond 800 nm are not in the EEM) and 0 beyond it.
  const Dye d;
  Synthetic s;
  s.ex = grid(250, 600, 5);
  s.em = grid(300, 800, 2);
  double rowPeak = 0;
  for (double x : s.ex) rowPeak = std::max(rowPeak, d.absorptance(x));
  double window = 0;
  for (double m = 300; m < 800; m += 0.01) window += d.emission(m) * 0.01;
  EemLayout l = scatterLayout();
  l.meanEmissionShape = true; // Raman crosses the peak (see ABandOverTheEmissionPeak)
  const RM got = import(s.csv(d), l, given(d.yield), peak(d.aMax));
  double worst = 0, scale = 0;
  for (int i = RM::binOf(300); i <= RM::binOf(597); ++i)
    for (int o = i + 1; o < RM::kBins; ++o) {
      const double li = RM::centre(i), lo = RM::centre(o);
      // The EEM samples the absorption edge every 5 nm: between rows it is linear.
      const double x0 = 250 + 5 * std::floor((li - 250) / 5), u = (li - x0) / 5;
      // <peak> is the absorptance of the EEM's strongest row.
      const double a = ((1 - u) * d.absorptance(x0) + u * d.absorptance(x0 + 5)) * d.aMax / rowPeak;
      const double want =
          lo < 800 ? a * d.yield * d.emission(lo) / window * RM::kBinNm * li / lo : 0.0;
      scale = std::max(scale, want);
      worst = std::max(worst, std::abs(got(i, o) - want));
    }
  EXPECT_LT(worst / scale, 0.02);
}

TEST(EemImport, OrientationAndUnitsDoNotChangeTheMatrix) {
  const Dye d;
  Synthetic s;
  s.ex = grid(300, 600, 5);
  s.em = grid(300, 900, 2);
  const RM base = import(s.csv(d), scatterLayout(), given(d.yield), peak(d.aMax));
  Synthetic t = s;
  t.emissionRows = true;
  EemLayout l = scatterLayout();
  l.emissionRows = true;
  EXPECT_LT(worstError(import(t.csv(d), l, given(d.yield), peak(d.aMax)), base, 300, 600), 1e-9);
  Synthetic e = s;
  e.energy = true;
  EemLayout le = scatterLayout();
  le.energyUnits = true;
  EXPECT_LT(worstError(import(e.csv(d), le, given(d.yield), peak(d.aMax)), base, 300, 600), 1e-9);
  // Read as photons, an energy table tilts the emission towards short wavelengths: detectable.
  EXPECT_GT(
      worstError(import(e.csv(d), scatterLayout(), given(d.yield), peak(d.aMax)), base, 300, 600),
      0.01);
}

TEST(EemImport, GivenAbsorptanceNormalisesEachRow) {
  // With A(lambda) given (a dilute solution's EEM: its profile is not the surface's), each row
  // is normalised to Q A(ex); the instrument's scale and the row's count level drop out.
  const Dye d;
  Synthetic s = onTheMatrixGrid();
  s.k = 123.0;
  s.raman = 0;
  EemAbsorptance a;
  a.spectrum = [&](double nm) { return d.absorptance(nm); };
  EemSummary sum;
  const RM got = import(s.csv(d), scatterLayout(12, false), given(d.yield), a, &sum);
  EXPECT_LT(worstError(got, RM::fromModel(d.model()), 400, 520), 0.01);
  // Rows with almost no counts get the mean emission shape, and are counted.
  EXPECT_GT(sum.meanShapeRows, 0u);
  EemLayout mean = scatterLayout();
  mean.meanEmissionShape = true;
  EXPECT_LT(
      worstError(import(s.csv(d), mean, given(d.yield), a), RM::fromModel(d.model()), 302.5, 647.5),
      0.01);
}

TEST(EemImport, QuantumYieldFromAReferenceDye) {
  // The relative method: sample and reference measured alike (same instrument scale k);
  // Q = Q_R (S / A) / (S_R / A_R) recovers the sample's yield.
  Dye sample, ref;
  sample.yield = 0.37;
  ref.la = 490, ref.stokes = 25, ref.yield = 0.95, ref.aMax = 0.05;
  Synthetic s;
  s.ex = grid(300, 600, 5);
  s.em = grid(300, 1100, 2);
  s.raman = 0;
  const EemLayout l = scatterLayout(8, false);
  EemSummary tmp;
  const EemTable refTable = withoutScatter(parseEemCsv(s.csv(ref), "ref.csv", l), l, tmp);
  EemYield y;
  y.reference = &refTable;
  y.referenceYield = ref.yield;
  y.referenceAbsorptance = ref.absorptance(500);
  y.referenceExcitationNm = 500;
  EemAbsorptance a;
  a.spectrum = [&](double nm) { return sample.absorptance(nm); };
  EemSummary sum;
  import(s.csv(sample), l, y, a, &sum);
  EXPECT_NEAR(sum.quantumYield, sample.yield, 0.01 * sample.yield);
  // A reference absorptance written too large gives a yield above 1: refused, with numbers.
  y.referenceAbsorptance *= 10;
  expectError([&] { import(s.csv(sample), l, y, a); }, "quantum yield at most 1");
  y.referenceAbsorptance /= 10;
  y.referenceExcitationNm = 700;
  expectError([&] { import(s.csv(sample), l, y, a); }, "reference excitation 700 nm within");
}

TEST(EemImport, NegativeCellsAndEmptyEems) {
  // Dark-subtraction noise: a negative cell outside the bands is set to 0 and counted.
  const std::string noisy = "ex\\em,300,310,320\n300,5,-2,1\n310,1,9,-3\n";
  EemSummary sum;
  EemLayout l;
  l.rayleighWidthNm = 4;
  const EemTable t = withoutScatter(parseEemCsv(noisy, "n.csv", l), l, sum);
  EXPECT_EQ(sum.negativeCells, 2u);
  EXPECT_EQ(sum.scatterCells, 2u);
  for (double c : t.counts) EXPECT_GE(c, 0);
  // Nothing left once the bands are removed: refused.
  const std::string onlyScatter = "ex\\em,300,310,320\n300,5,0,0\n310,0,9,0\n";
  EemSummary s2;
  EemLayout wide;
  wide.rayleighWidthNm = 4;
  wide.secondOrder = false;
  const EemTable empty = withoutScatter(parseEemCsv(onlyScatter, "e.csv", wide), wide, s2);
  expectError([&] { donaldsonFromEem(empty, wide, given(0.5), peak(0.5), s2); },
              "e.csv: expected an EEM with emission left");
  // Malformed tables name file:line.
  expectError([&] { parseEemCsv("ex\\em,300,310\n300,1\n", "bad.csv", l); },
              "bad.csv:2: expected 3");
  expectError([&] { parseEemCsv("ex\\em,300,310\n50,1,2\n60,1,2\n", "bad.csv", l); },
              "excitation wavelengths in nm within [100, 2000], found 50");
  EemLayout rows;
  rows.emissionRows = true;
  expectError([&] { parseEemCsv("em\\ex,300,290\n300,1,2\n310,1,2\n", "t.csv", rows); },
              "increasing excitation wavelengths");
}

TEST(EemImport, AnyFiniteScaleImportsTheSameMatrix) {
  // Counts reaching 1e308 overflowed the row integrals (the matrix became 0 and the image the
  // plain surface's); subnormal counts lost digits. Only their proportions matter.
  const Dye d;
  Synthetic s;
  s.ex = grid(300, 600, 5);
  s.em = grid(300, 1100, 2);
  s.raman = 0;
  const EemLayout l = scatterLayout(8, false);
  const RM base = import(s.csv(d), l, given(d.yield), peak(d.aMax));
  for (const double f : {1.7e302, 1e-314}) { // largest cell 1.7e308, smallest subnormal
    Synthetic scaled = s;
    scaled.k *= f, scaled.rayleigh *= f, scaled.raman *= f;
    const double tolerance = f < 1 ? 1e-4 : 1e-9; // subnormals keep about 5 digits
    EXPECT_LT(worstError(import(scaled.csv(d), l, given(d.yield), peak(d.aMax)), base, 300, 600),
              tolerance)
        << f;
    EemAbsorptance a;
    a.spectrum = [&](double nm) { return d.absorptance(nm); };
    EXPECT_LT(worstError(import(scaled.csv(d), l, given(d.yield), a),
                         import(s.csv(d), l, given(d.yield), a), 300, 600),
              tolerance)
        << f;
  }
  // The relative method: a reference measured alike keeps the yield at any common scale; a
  // reference of 1e308 counts was "found no reference emission".
  Dye ref;
  ref.la = 490, ref.stokes = 25, ref.yield = 0.95, ref.aMax = 0.05;
  auto yieldWith = [&](double sampleScale, double refScale) {
    Synthetic a = s, b = s;
    a.k *= sampleScale, a.rayleigh *= sampleScale, a.raman *= sampleScale;
    b.k *= refScale, b.rayleigh *= refScale, b.raman *= refScale;
    EemSummary tmp, sum;
    const EemTable refTable = withoutScatter(parseEemCsv(b.csv(ref), "ref.csv", l), l, tmp);
    EemYield y;
    y.reference = &refTable;
    y.referenceYield = ref.yield;
    y.referenceAbsorptance = ref.absorptance(500);
    y.referenceExcitationNm = 500;
    EemAbsorptance abs;
    abs.spectrum = [&](double nm) { return d.absorptance(nm); };
    import(a.csv(d), l, y, abs, &sum);
    return sum.quantumYield;
  };
  const double q = yieldWith(1, 1);
  EXPECT_NEAR(q, d.yield, 0.02);
  EXPECT_NEAR(yieldWith(1.7e302, 1.7e302), q, 1e-9 * q);
  EXPECT_NEAR(yieldWith(1e-314, 1e-314), q, 1e-4 * q);
  EXPECT_NEAR(yieldWith(1.0, 2.0), q / 2, 1e-9 * q); // a stronger reference: a lower yield
  // A reference 1e302 times stronger than the sample: a yield of ~1e-302 models nothing.
  expectError([&] { yieldWith(1, 1.7e302); },
              "dye.csv: expected a quantum yield of at least 1e-06 from the reference dye ref.csv, "
              "found 3");
}

TEST(EemImport, EemsTheMatrixCannotModelAreRefused) {
  // Each imported to (nearly) nothing with at most a note.
  const Dye d;
  Synthetic s;
  s.ex = grid(300, 600, 5);
  s.em = grid(300, 900, 2);
  const EemLayout l = scatterLayout();
  // A transposed table read without layout="emission_rows": its cells with emission longer
  // than excitation are the anti-Stokes side of the real table.
  Synthetic transposed = s;
  transposed.emissionRows = true;
  try {
    import(transposed.csv(d), l, given(d.yield), peak(d.aMax));
    ADD_FAILURE() << "a transposed table was imported";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("dye.csv: expected an EEM whose emission the matrix models (emission longer "
                     "than its excitation, both within 300-1100 nm), found "),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("a transposed table? rows are excitation wavelengths unless "
                     "layout=\"emission_rows\""),
              std::string::npos)
        << m;
  }
  // Read as what it is, it imports.
  EemLayout rows = l;
  rows.emissionRows = true;
  EemSummary sum;
  import(transposed.csv(d), rows, given(d.yield), peak(d.aMax), &sum);
  EXPECT_GT(sum.modelledFraction, 0.95);
  EXPECT_NEAR(sum.modelledFraction + sum.antiStokesFraction + sum.outsideGridFraction, 1, 0.01);
  // Wholly outside 300-1100 nm (a short-wave infrared dye).
  Dye infrared;
  infrared.la = 1250, infrared.stokes = 150;
  Synthetic far;
  far.ex = grid(1150, 1400, 5);
  far.em = grid(1200, 1700, 5);
  far.rayleigh = far.raman = 0;
  expectError([&] { import(far.csv(infrared), EemLayout{}, given(0.5), peak(0.5)); },
              "found 0% of the emitted photons modelled, 0.00");
  expectError([&] { import(far.csv(infrared), EemLayout{}, given(0.5), peak(0.5)); },
              "% below their excitation wavelength (anti-Stokes, not modelled), 99.99");
  // Anti-Stokes only: every emission column below every excitation row.
  std::ostringstream anti;
  anti << "ex\\em";
  for (int em = 300; em <= 480; em += 10) anti << "," << em;
  anti << "\n";
  for (int ex = 500; ex <= 600; ex += 10) {
    anti << ex;
    for (int em = 300; em <= 480; em += 10) anti << "," << 1 + (em - 300) / 10;
    anti << "\n";
  }
  expectError([&] { import(anti.str(), EemLayout{}, given(0.5), peak(0.5)); },
              "found 0% of the emitted photons modelled, 100% below");
  // Half modelled, half beyond 1100 nm: imported (the scene build warns: see the fluorescence
  // tests), with the shares in its summary.
  Dye edge;
  edge.la = 1000, edge.stokes = 100, edge.skew = 0;
  Synthetic half;
  half.ex = grid(950, 1050, 5);
  half.em = grid(960, 1300, 5);
  half.rayleigh = half.raman = 0;
  EemSummary edgeSum;
  import(half.csv(edge), EemLayout{}, given(0.5), peak(0.5), &edgeSum);
  EXPECT_GT(edgeSum.outsideGridFraction, 0.5);
  EXPECT_LT(edgeSum.modelledFraction, kEemWarnModelledFraction);
  EXPECT_GT(edgeSum.modelledFraction, kEemMinModelledFraction);
}

} // namespace
} // namespace nx
