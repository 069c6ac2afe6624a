#pragma once
// How an instrument wrote its excitation-emission matrix and which scatter bands it holds
// (a scene's <eem> attributes; spectra/eem_import.h uses them).

namespace nx {

/// Raman shift of liquid water's O-H stretch band, about 3400 cm^-1 (raman_shift="water"):
/// at 350 nm excitation its peak is at 397 nm, the band of Lawaetz & Stedmon 2009.
inline constexpr double kWaterRamanShiftCm = 3400;

/// How the instrument wrote its table and which scatter it contains.
struct EemLayout {
  bool emissionRows = false;      ///< rows are emission wavelengths (columns excitation)
  bool energyUnits = false;       ///< cells are energy per nm (else photons per nm, the default)
  double rayleighWidthNm = 0;     ///< full width of the band removed around em = ex and em = 2 ex
  bool secondOrder = true;        ///< also remove the second-order Rayleigh line em = 2 ex
  double ramanShiftCm = 0;        ///< Raman shift of the solvent in cm^-1 (0: no Raman band)
  double ramanWidthNm = 0;        ///< full width of the removed Raman band
  bool meanEmissionShape = false; ///< one emission shape for every row (Kasha's rule)
};

} // namespace nx
