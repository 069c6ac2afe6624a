#pragma once
// An instrument excitation-emission matrix (EEM) turned into an absolute Donaldson matrix:
// scatter bands removed, counts normalised by a quantum yield and an absorptance, photons
// turned into energy (docs/eem-import.md gives the method and its choices).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/params/eem_layout.h"
#include "spectra/reradiation_matrix.h"

namespace nx {

/// An instrument EEM as read: counts[row * emissionNm.size() + col], excitation rows.
struct EemTable {
  std::vector<double> excitationNm, emissionNm, counts;
  std::vector<char> removed; ///< per cell: inside a scatter band (set by withoutScatter)
  std::string source;        ///< file name for messages
  /// The counts as written were these times larger: parseEemCsv divides them by their largest
  /// magnitude, so that any finite scale (1e308 or 1e-318) imports to the same matrix.
  double scale = 1;
};

/// What the absolute scale comes from: a quantum yield, or a reference dye of known yield
/// measured with the same instrument and settings (the relative method).
struct EemYield {
  std::optional<double> quantumYield;  ///< photons emitted per photon absorbed
  const EemTable* reference = nullptr; ///< or the reference dye's EEM (scatter removed alike)
  double referenceYield = 0;           ///< its quantum yield
  double referenceAbsorptance = 0;     ///< its absorptance at the reference excitation
  std::optional<double> referenceExcitationNm; ///< default: the reference's excitation peak
};

/// Where the absorptance comes from: a spectrum, or the EEM's own excitation profile scaled
/// to a peak absorptance (valid for a front-face measurement of the surface itself).
struct EemAbsorptance {
  std::function<double(double)> spectrum; ///< A(lambda), when given
  std::optional<double> peak;             ///< a_max for the excitation-profile form
};

/// What the import did, for the log and the tests.
struct EemSummary {
  size_t scatterCells = 0;       ///< cells inside a Rayleigh or Raman band, interpolated over
  size_t negativeCells = 0;      ///< negative cells outside the bands, set to 0
  size_t meanShapeRows = 0;      ///< rows too weak for their own shape (the mean one used)
  double quantumYield = 0;       ///< the yield used (given or from the reference)
  double antiStokesFraction = 0; ///< share of the emitted photons below the excitation
  /// Share of the emitted photons whose excitation or emission lies outside the matrix's grid
  /// (300-1100 nm).
  double outsideGridFraction = 0;
  /// Share of the emitted photons the matrix models: both wavelengths on its grid and the
  /// emission in a longer 5 nm bin than the excitation (1 - the two shares above, but for
  /// emission inside the excitation's own bin). Cells at equal wavelengths (the elastic line)
  /// count in none of the shares.
  double modelledFraction = 0;
  /// emission_shape="mean": share of the counts outside the bands the one shape explains,
  /// 1 - |residual|^2 / |counts|^2 (near 1 when Kasha's rule holds); -1 otherwise
  double meanShapeFit = -1;
  /// One line saying all of the above (and what the elastic part is).
  std::string text() const;
  /// What became of the emitted photons: the modelled, anti-Stokes and off-grid shares.
  std::string coverageText() const;
};

/// Reads an EEM CSV (first row: a label cell and the column wavelengths; then per row its
/// wavelength and counts, any finite numbers), transposed when layout.emissionRows, and divides
/// the counts by their largest magnitude (kept in EemTable::scale). Errors name source:line.
EemTable parseEemCsv(const std::string& text, const std::string& source, const EemLayout& layout);

/// The EEM with its scatter bands and negative cells handled (Zepp et al. 2004; Bahram et al.
/// 2006): cells within half a width of em = ex, em = 2 ex (secondOrder) and the Raman line
/// 1 / (1 / ex - shift) are replaced by linear interpolation along the emission axis between
/// the nearest cells outside the band (a band at the grid's end: 0 on that side); negative
/// cells elsewhere are set to 0. Energy units are turned into relative photon counts.
EemTable withoutScatter(const EemTable& t, const EemLayout& layout, EemSummary& summary);

/// The absolute Donaldson matrix (fluorescence only, energy fraction per emission cell) of an
/// EEM already passed through withoutScatter: photons emitted at em per photon incident at ex,
/// per nm, P(ex, em) = Q A(ex) p(ex, em) with p the row's emission shape (counts over their
/// integral S(ex); weak rows take the mean shape), or with A from the excitation profile
/// P = Q a_max I(ex, em) / max_ex S(ex); the energy fraction is P ex / em. With
/// meanEmissionShape the counts are first replaced by the rank-1 model I = s(ex) p(em) fitted
/// by alternating least squares to the cells outside the bands only (Kasha's rule; a
/// one-component PARAFAC, Bro 1997), so a band over the emission peak biases nothing. Throws
/// nx::Error for a yield above 1, an EEM without emission, a missing reference row, or an EEM
/// of which under kEemMinModelledFraction of the emitted photons can be modelled (wholly
/// outside 300-1100 nm, transposed, anti-Stokes).
/// Below this share of its emitted photons modelled (EemSummary::modelledFraction) an EEM is
/// refused: what it describes is not what the matrix can render.
inline constexpr double kEemMinModelledFraction = 0.01;

/// Below this share modelled, an import warns (most of the dye's light is missing).
inline constexpr double kEemWarnModelledFraction = 0.5;

MeasuredMatrix donaldsonFromEem(const EemTable& clean, const EemLayout& layout,
                                const EemYield& yield, const EemAbsorptance& absorptance,
                                EemSummary& summary);

} // namespace nx
