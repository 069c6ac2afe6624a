#pragma once
// The Glassner re-radiation (Donaldson) matrix of a fluorescent surface on a 5 nm grid,
// and its sampling from the camera side (see the fluorescence model document).

#include "core/cell_index.h"
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "spectra/spectrum.h"

namespace nx {

/// Parameters of the skew-Cauchy model of a fluorescent surface.
struct FluorescenceModel {
  double absorptionPeakNm = 460; ///< location l_a of the absorption curve
  double stokesNm = 100;         ///< emission location = l_a + Stokes shift
  double widthNm = 20;           ///< g
  double skew = 10;              ///< w: absorption uses -w, emission +w
  double quantumYield = 1;       ///< Q
  double peakAbsorptance = 1;    ///< a_max
};

/// A measured Donaldson matrix as read from a CSV file: cells[row * emission.size() + col]
/// for excitation row and emission column; the diagonal (equal wavelengths) is reflectance.
struct MeasuredMatrix {
  std::vector<double> excitationNm, emissionNm, cells;
  std::string source; ///< file name for messages
  /// Fluorescence only (an imported EEM): cells where excitation equals emission are not a
  /// diagonal, and the elastic part is the surface's reflectance.
  bool fluorescenceOnly = false;
};

/// How ReradiationMatrix::fromMeasured resamples a measured matrix onto its 5 nm grid: a linear
/// map from the measured cells to the grid's cells and diagonal bins. fromMeasured applies it;
/// a gradient takes a measured cell's tangent from it (no resampled copies per cell).
struct MeasuredResampling {
  /// Measured cell `input` (row * columns + column) reaches `output` with weight w: grid cell
  /// i * kBins + o, or kBins^2 + o for the diagonal (elastic part) of bin o.
  struct Term {
    uint32_t input, output;
    double w;
  };
  std::vector<Term> terms; ///< grouped by output, in increasing order
  /// Output index of bin o's diagonal.
  static uint32_t diagonal(int o);
};

/// fromMeasured's resampling of a matrix of m's wavelengths (m's cells are not read): each
/// off-diagonal grid cell bilinear in the four measured cells around it (as densities per nm
/// of emission, times 5 nm; cells with emission not longer than excitation count as 0), each
/// diagonal bin linear in the two measured diagonal cells around it.
MeasuredResampling measuredResampling(const MeasuredMatrix& m);

/// FNV-1a of a measured matrix's numbers (wavelengths and cells): its identity in render keys.
uint64_t measuredMatrixDigest(const MeasuredMatrix& m);

/// What next-event estimation knows of a light's spectrum on the matrix's grid: the mean of its
/// emission over each 5 nm bin (any non-negative shape: only its proportions matter) and the
/// bins [lo, hi) outside which it is zero.
struct ExcitationGuide {
  std::array<float, 160> mean{}; ///< per bin of ReradiationMatrix
  int lo = 0, hi = 160;          ///< support
};

/// The guide of a light whose spectrum is s: its mean over each 5 nm bin (20 points per bin, at
/// the centres of 0.25 nm steps) and the bins where it is not zero; a flat guide for null.
ExcitationGuide excitationGuideOf(const Spectrum* s);

/// Two excitation events for one lane with their multi-sample MIS weights
/// (ReradiationMatrix::guidedExcitation): [0] the column's, [1] the light-guided one.
struct GuidedExcitation {
  float nm[2];     ///< excitation wavelengths (the lane's own for an elastic event)
  float weight[2]; ///< what each event's light is multiplied by
};

/// Most guides one light's excitation events are drawn for (a relightable render's relighting
/// targets of one light group; a plain render's light has one).
inline constexpr int kMaxExcitationGuides = 8;

/// The guides of one light: its spectrum's, or one per relighting target of its group.
struct ExcitationGuides {
  const ExcitationGuide* guide[kMaxExcitationGuides] = {}; ///< the first `count` are set
  int count = 0;
};

/// The column's event and one per guide (ReradiationMatrix::guidedExcitations): [0] the
/// column's, [1 + t] guide t's.
struct GuidedExcitations {
  float nm[1 + kMaxExcitationGuides];     ///< excitation wavelengths
  float weight[1 + kMaxExcitationGuides]; ///< what each event's light is multiplied by
};

/// M[i][o] (energy re-radiated from excitation bin i into emission bin o, o > i), the
/// absorptance a per bin, and per-column sampling tables.
class ReradiationMatrix {
public:
  /// Number of 5 nm bins covering [300, 1100) nm: the whole range a sensor can see, so that
  /// emission in the near infrared lands where it belongs (a 360-830 nm grid renormalised a
  /// 910 nm emission into its last bin).
  static constexpr int kBins = 160;
  static constexpr double kMinNm = 300, kBinNm = 5;
  /// End of the grid (nm): kMinNm + kBins kBinNm.
  static constexpr double kMaxNm = kMinNm + kBins * kBinNm;

  /// Bin containing nm, or -1 outside [300, 1100).
  static int binOf(double nm) {
    const double x = (nm - kMinNm) / kBinNm;
    return x >= 0 && x < kBins ? static_cast<int>(x) : -1;
  }
  /// Centre of bin i (nm).
  static double centre(int i) { return kMinNm + (i + 0.5) * kBinNm; }

  /// The matrix of the skew-Cauchy model (Zheng et al. 2014 curves):
  /// a(l) = a_max f(l; l_a, g, -w) / max f, e(l) = f(l; l_a + S, g, +w) normalised over the
  /// grid, M[i][o] = a_i Q e_o l_i / l_o for o > i, 0 otherwise.
  static ReradiationMatrix fromModel(const FluorescenceModel& m);

  /// The separable matrix of a dye given as a datasheet gives it: absorptance a_i in [0, 1] and
  /// an emission spectrum in photons of any scale (e_o, normalised here to sum 1 over the grid)
  /// at the bins' centres, and the quantum yield Q: M[i][o] = a_i Q e_o l_i / l_o for o > i
  /// (fromModel is this with the model's curves). Throws nx::Error when e is 0 everywhere.
  static ReradiationMatrix fromSpectra(const std::array<double, kBins>& absorptance,
                                       const std::array<double, kBins>& emission,
                                       double quantumYield);

  /// A measured matrix resampled onto the grid: off-diagonal cells (emission longer than
  /// excitation) as a bilinearly interpolated density per nm of emission times 5 nm; the
  /// diagonal gives the elastic reflectance D. Cells with emission shorter than excitation
  /// are ignored (anti-Stokes light is not modelled). A matrix without a diagonal (no
  /// excitation wavelength equal to an emission one: fluorescence only, as an instrument EEM)
  /// takes its elastic part from the surface's reflectance rho instead; `rho`, when given, is
  /// then checked with it for energy (rho + re-radiated <= 1 at every excitation bin). An
  /// imported EEM (m.fluorescenceOnly) always takes its elastic part from rho.
  static ReradiationMatrix fromMeasured(const MeasuredMatrix& m, const Spectrum* rho = nullptr);
  /// A measured matrix whose elastic part is the surface's reflectance (it has no diagonal).
  bool elasticFromReflectance() const { return elasticFromRho_; }
  /// A measured matrix whose diagonal is there but all zero (taken as missing).
  bool zeroDiagonal() const { return zeroDiagonal_; }

  /// Absorptance of bin i (parametric model; 0 for measured matrices, whose D is explicit).
  double absorptance(int i) const { return absorptance_[i]; }
  /// M[i][o].
  double operator()(int i, int o) const { return m_[static_cast<size_t>(i) * kBins + o]; }
  /// c(o) = sum over i of M[i][o]: the re-radiated part of the lobe's albedo at bin o.
  double columnSum(int o) const { return columnSum_[o]; }
  /// True for a measured matrix: the elastic part is `measuredDiagonal`, not (1 - a) rho.
  bool measured() const { return measured_; }

  /// Elastic part D at bin o for a surface of reflectance rhoValue at the lane's wavelength:
  /// (1 - a_o) rho (model) or the measured diagonal.
  double elastic(int o, double rhoValue) const {
    if (elasticFromRho_) return rhoValue;
    return measured_ ? diagonal_[o] : (1 - absorptance_[o]) * rhoValue;
  }

  /// Camera-to-light sampling for a lane at wavelength nm (bin o): returns the new (excitation)
  /// wavelength and multiplies `weight` by D(o) + c(o). Elastic with probability
  /// D / (D + c), otherwise bin i with probability M[i][o] / c(o) and a wavelength uniform
  /// in it (u picks the event, v the position in the bin). Outside the grid the surface is
  /// an ordinary reflector of rho.
  /// Single precision and inline: it runs for every lane at every fluorescent vertex.
  float sampleExcitation(float nm, float rhoValue, float u, float v, float& weight) const {
    const float x = (nm - static_cast<float>(kMinNm)) * static_cast<float>(1.0 / kBinNm);
    if (!(x >= 0 && x < static_cast<float>(kBins))) {
      weight *= measured_ && !elasticFromRho_ ? 0.0f : rhoValue;
      return nm;
    }
    const int o = static_cast<int>(x);
    const ColumnSampling& col = columns_[o];
    const float d = col.elasticScale * rhoValue + col.elasticConstant;
    const float total = d + col.sum;
    weight *= total;
    const float target = u * total - d;
    if (!(target >= 0) || !(col.sum > 0)) return nm; // elastic
    return static_cast<float>(kMinNm) +
           (static_cast<float>(excitationBin(o, target)) + v) * static_cast<float>(kBinNm);
  }

  /// sampleExcitation for a dye at relative concentration k in [0, 1] (a concentration map):
  /// absorptance k a, so the cells k M[i][o] and the elastic part (1 - k a_o) rho (an imported
  /// EEM's elastic part is rho whatever k). Kept apart from sampleExcitation so that surfaces
  /// without a map run its exact arithmetic.
  float sampleExcitationScaled(float nm, float rhoValue, float k, float u, float v,
                               float& weight) const {
    const float x = (nm - static_cast<float>(kMinNm)) * static_cast<float>(1.0 / kBinNm);
    if (!(x >= 0 && x < static_cast<float>(kBins))) {
      weight *= rhoValue;
      return nm;
    }
    const int o = static_cast<int>(x);
    const ColumnSampling& col = columns_[o];
    const float d = (1 - k * (1 - col.elasticScale)) * rhoValue;
    const float sum = k * col.sum;
    const float total = d + sum;
    weight *= total;
    const float target = u * total - d;
    if (!(target >= 0) || !(sum > 0)) return nm; // elastic
    return static_cast<float>(kMinNm) +
           (static_cast<float>(excitationBin(o, target / k)) + v) * static_cast<float>(kBinNm);
  }
  /// Next-event estimation's excitation choice for a lane at wavelength nm (bin o), towards a
  /// light whose spectrum's bin means are `guide`: the column's event `columnNm` (what
  /// sampleExcitation or sampleExcitationScaled returned for this lane) and a second event drawn
  /// in proportion to the column times the guide, v(e) g(e) with v = D for the elastic event
  /// and k M[i][o] for bin i (u picks it, v its position in the bin). Both carry their
  /// power-heuristic weight of multi-sample MIS (Veach & Guibas 1995, beta = 2): with
  /// C = D + k c, Z = sum over e of v(e) g(e) and r(e) = p_guided / p_column = g(e) C / Z, the
  /// column's event multiplies its light by C / (1 + r^2), the guided one by C / (r + 1 / r),
  /// so E[w_c L(nm_c) + w_g L(nm_g)] = D L(nm) + sum_i k M[i][o] Lbar_i for any light (the
  /// guide only moves samples towards where it shines; where it is dark the column's event
  /// keeps its plain weight). The power heuristic, not the balance one: where the guide
  /// describes the light, the column's events in the light's bins count next to nothing
  /// instead of half, which lowers the dye card's noise under a narrow lamp
  /// (docs/performance.md). A dark column (Z = 0) gives the guided event weight 0 and the
  /// column's its plain weight C.
  GuidedExcitation guidedExcitation(float nm, float columnNm, float rhoValue, float k,
                                    const ExcitationGuide& guide, float u, float v) const {
    ExcitationGuides one;
    one.guide[0] = &guide;
    one.count = 1;
    const Sample2Pair uv{u, v};
    GuidedExcitations e;
    guidedExcitations(nm, columnNm, rhoValue, k, one, &uv, e);
    return {{e.nm[0], e.nm[1]}, {e.weight[0], e.weight[1]}};
  }

  /// A (u, v) pair of one guided draw (u picks the event, v its position in the bin).
  struct Sample2Pair {
    float u, v;
  };

  /// guidedExcitation for several guides at once (a relightable render told several relighting
  /// targets): the column's event and one event per guide t, drawn in proportion to v(e) g_t(e)
  /// with uv[t], each with its power-heuristic weight among all the techniques (Veach & Guibas
  /// 1995): with q_c = 1 / C and q_t(e) = g_t(e) / Z_t, the event of technique s multiplies its
  /// light by q_s(e) / sum over techniques of q(e)^2, i.e. C / (1 + sum r_t^2) for the column's
  /// and C r_s / (1 + sum r_t^2) for guide s's, r_t = g_t(e) C / Z_t. For one guide these are
  /// guidedExcitation's weights; E[sum of weighted lights] = D L(nm) + sum_i k M[i][o] Lbar_i for
  /// any light. A guide dark on the column (Z_t = 0) gets an elastic event of weight 0; with no
  /// event at all (C = 0) every weight is 0.
  void guidedExcitations(float nm, float columnNm, float rhoValue, float k,
                         const ExcitationGuides& guides, const Sample2Pair* uv,
                         GuidedExcitations& out) const {
    const int n = guides.count;
    for (int t = 0; t <= n; ++t) out.weight[t] = 0, out.nm[t] = nm;
    out.nm[0] = columnNm;
    const float x = (nm - static_cast<float>(kMinNm)) * static_cast<float>(1.0 / kBinNm);
    if (!(x >= 0 && x < static_cast<float>(kBins))) { // an ordinary reflector (or black)
      const float d = measured_ && !elasticFromRho_ ? 0.0f : rhoValue;
      for (int t = 0; t <= n; ++t) out.weight[t] = d / static_cast<float>(n + 1);
      return;
    }
    const int o = static_cast<int>(x);
    const ColumnSampling& col = columns_[o];
    const float d = k == 1 ? col.elasticScale * rhoValue + col.elasticConstant
                           : (1 - k * (1 - col.elasticScale)) * rhoValue;
    const float columnTotal = d + k * col.sum;
    if (!(columnTotal > 0)) return;
    const float* cdf = &cdf_[static_cast<size_t>(o) * kBins];
    // Per guide: Z_t and the drawn event's bin (o for the elastic event, -1 for none).
    float z[kMaxExcitationGuides];
    int event[kMaxExcitationGuides];
    for (int t = 0; t < n; ++t) {
      const ExcitationGuide& guide = *guides.guide[t];
      // Running sums of M[i][o] g_i over the guide's support below o (no allocation).
      std::array<float, kBins> running;
      const int lo = guide.lo, hi = std::min(guide.hi, o);
      float sum = 0;
      for (int i = lo; i < hi; ++i) {
        const float cell = cdf[i] - (i > 0 ? cdf[i - 1] : 0.0f);
        running[static_cast<size_t>(i - lo)] = sum += cell * guide.mean[static_cast<size_t>(i)];
      }
      const float elasticGuided = d * guide.mean[static_cast<size_t>(o)];
      z[t] = elasticGuided + k * sum;
      event[t] = -1;
      if (!(z[t] > 0)) continue;
      const float target = uv[t].u * z[t] - elasticGuided;
      if (!(target >= 0) || !(sum > 0)) { // elastic
        event[t] = o;
        continue;
      }
      const int count = hi - lo;
      const auto first = running.begin();
      int i = lo +
              std::min(static_cast<int>(std::upper_bound(first, first + count, target / k) - first),
                       count - 1);
      while (i > lo &&
             running[static_cast<size_t>(i - lo)] == running[static_cast<size_t>(i - lo - 1)])
        --i; // only after the clamp: never an empty bin
      event[t] = i;
      out.nm[t + 1] = static_cast<float>(kMinNm) +
                      (static_cast<float>(i) + uv[t].v) * static_cast<float>(kBinNm);
    }
    // r_t(e) at event e (a bin, or o for the elastic one); 1 + the sum of the r^2 of the guides
    // other than `skip`. Written in r so that no square of a density overflows.
    const auto ratio = [&](int t, int e) {
      return z[t] > 0 && e >= 0 ? guides.guide[t]->mean[static_cast<size_t>(e)] * columnTotal / z[t]
                                : 0.0f;
    };
    const auto others = [&](int e, int skip) {
      float sum = 1;
      for (int t = 0; t < n; ++t)
        if (t != skip) {
          const float r = ratio(t, e);
          sum += r * r;
        }
      return sum;
    };
    const int columnBin = columnNm == nm ? o : binOf(columnNm);
    out.weight[0] = columnTotal / others(columnBin, -1);
    for (int t = 0; t < n; ++t)
      if (event[t] >= 0) { // C r / (r^2 + others) = C / (r + others / r)
        const float r = ratio(t, event[t]);
        out.weight[t + 1] = columnTotal / (r + others(event[t], t) / r);
      }
  }

  /// How unevenly the light whose bin means are `guide` is met by column o's own sampling:
  /// E[g^2] / E[g]^2 over the column's events (elastic with weight D at rho = 1, bin i with
  /// M[i][o]), i.e. 1 + the relative variance of the light's value at the column's choice. 1
  /// for a guide constant over the column, a column without events or a guide dark on it
  /// (guiding cannot help there); next-event estimation guides only where this is large.
  double guideMismatch(const ExcitationGuide& guide, int o) const;

  /// The elastic part at bin o for a dye at relative concentration k (see
  /// sampleExcitationScaled).
  double elastic(int o, double rhoValue, double k) const {
    if (elasticFromRho_) return rhoValue;
    return measured_ ? diagonal_[o] : (1 - k * absorptance_[o]) * rhoValue;
  }

  /// Writes the matrix as a CSV file (first row: emission bin centres; then per excitation
  /// bin its centre and the cells; the diagonal holds the elastic part for rho = 1).
  std::string toCsv() const;

private:
  void finish();
  /// The first bin i < o whose running sum in column o exceeds target (clamped to o - 1 and
  /// never an empty bin): the inverse CDF, so stratified samples stay stratified. The search
  /// starts at the guide table's entry and takes a step or two.
  int excitationBin(int o, float target) const {
    const float* cdf = &cdf_[static_cast<size_t>(o) * kBins];
    const int j = cellIndex(target * columns_[o].guideScale, kGuide);
    int i = std::min(static_cast<int>(guide_[static_cast<size_t>(o) * kGuide + j]), o - 1);
    while (i < o - 1 && cdf[i] <= target) ++i;
    while (i > 0 && cdf[i - 1] > target) --i;
    while (i > 0 && cdf[i] == cdf[i - 1]) --i; // only after the clamp: skip empty bins
    return i;
  }

  /// What sampling needs of column o, in one place: D = elasticScale rho + elasticConstant
  /// ((1 - a) rho for the model, the diagonal for measured matrices), c(o), kGuide / c(o).
  struct ColumnSampling {
    float elasticScale = 0, elasticConstant = 0, sum = 0, guideScale = 0;
  };
  /// Guide table (Chen & Asau 1974) entries per column.
  static constexpr int kGuide = 64;
  std::array<ColumnSampling, kBins> columns_{};
  std::vector<float> cdf_;     ///< [o][i]: running sums of M[.][o] over i
  std::vector<uint8_t> guide_; ///< [o][j]: first bin whose running sum exceeds j/kGuide of c(o)

  bool measured_ = false, elasticFromRho_ = false, zeroDiagonal_ = false;
  std::array<double, kBins> absorptance_{}, diagonal_{}, columnSum_{};
  std::vector<double> m_ = std::vector<double>(static_cast<size_t>(kBins) * kBins, 0.0);
};

/// Reads a Donaldson matrix CSV (first row: a label cell, then emission wavelengths; then
/// one row per excitation wavelength: the wavelength and the cells). Errors name file:line.
MeasuredMatrix readMeasuredMatrixCsv(const std::string& path);

/// The same from CSV text; `source` names it in messages.
MeasuredMatrix parseMeasuredMatrixCsv(const std::string& text, const std::string& source);

/// The grid table both forms share (first row: a label cell and the column wavelengths; then
/// rows of a wavelength and its cells): cells in [0, 1] when `fractions`, else any finite
/// number (instrument counts). Errors name source:line and the axes by rowAxis / columnAxis
/// ("excitation", "emission"); the result's excitationNm holds the rows' wavelengths.
/// `bytesPerCell`: the memory the caller will hold per cell beyond the table's own (checked
/// before parsing, parseNumberTable).
MeasuredMatrix parseWavelengthGrid(const std::string& text, const std::string& source,
                                   bool fractions, const std::string& rowAxis,
                                   const std::string& columnAxis, double bytesPerCell = 8);

/// Widths (nm) of the cells of a wavelength grid: half the distance between a cell's
/// neighbours (one-sided at the ends), so that a fraction per cell / width is a density per nm.
std::vector<double> gridCellWidths(const std::vector<double>& nm);

/// Photons re-radiated into each emission bin o for one unit of photons in every excitation
/// bin: sum over i of M[i][o] centre(o) / centre(i) (M holds energy fractions).
std::vector<double> emittedPhotonsPerBin(const ReradiationMatrix& m);

/// Checks a matrix given as numbers (not read from a CSV file): at least two increasing
/// excitation and emission wavelengths within the traced range's neighbourhood, one finite
/// cell in [0, 1] per pair. Throws nx::Error "<where>: expected ..., found ...".
void checkMeasuredMatrix(const MeasuredMatrix& m, const std::string& where);

/// The separable matrix of a dye given by spectra (<fluorescence> with <absorptance> and
/// <emission>): each bin takes the spectra's mean over it (spectrumMean). On a surface the
/// absorptance must lie in [0, 1] at every wavelength; with `normaliseAbsorptance` (a medium's
/// dye) it is a shape, scaled to 1 at its largest bin (and must be above 0 somewhere). The
/// emission (photons, any scale) must be non-negative and above 0 somewhere. A dye of which
/// under kEemMinModelledFraction of the emission lies above the absorption (what the matrix
/// models) is refused, under kEemWarnModelledFraction warned about in `warning` (if given).
/// Throws nx::Error "<where>: expected ..., found ...".
ReradiationMatrix separableMatrix(const Spectrum& absorptance, const Spectrum& emission,
                                  double quantumYield, bool normaliseAbsorptance,
                                  const std::string& where, std::string* warning = nullptr);

} // namespace nx
