#pragma once
// The transport of a relightable render (--relightable, docs/relighting.md): per pixel and light
// source (the emitters of a light group that share a spectrum), what one unit of the source's
// emission spectrum in each excitation bin puts into each band, on the sparse pattern of (band,
// bin) pairs the scene can reach. The image under new spectra S_s is the sum over sources and
// bins of T S_s(bin).

#include <cstdint>
#include <string>
#include <vector>

namespace nx {

/// The excitation grid: bins of stepNm from firstNm up to kRelightMaxNm.
struct RelightGrid {
  double firstNm = 300; ///< the first bin's start (the traced range's start)
  double stepNm = 5;    ///< bin width
  int bins = 160;       ///< bins up to 1100 nm

  /// The grid of `stepNm` over [300, 1100) nm.
  static RelightGrid withStep(double stepNm);
  /// Start of bin j (nm).
  double lo(int j) const { return firstNm + stepNm * j; }
  /// Centre of bin j (nm).
  double centre(int j) const { return firstNm + stepNm * (j + 0.5); }
  /// Bin containing nm (the range's end in the last bin), or -1 outside the grid.
  int binOf(float nm) const {
    const float x = (nm - static_cast<float>(firstNm)) * static_cast<float>(1.0 / stepNm);
    if (!(x >= 0)) return -1;
    const int j = static_cast<int>(x);
    return j < bins ? j : (x <= static_cast<float>(bins) ? bins - 1 : -1);
  }
};

/// The finest relight step (nm).
inline constexpr double kMinRelightStepNm = 0.1;

/// Checks a relight step (nm): from kMinRelightStepNm to 100, a divisor of 5 nm (0.1, 0.25, 1,
/// 2.5, ...) or a multiple of it, so that the bins nest with the 5 nm re-radiation grid.
/// Throws nx::Error naming `option`.
void checkRelightStep(double stepNm, const std::string& option);

/// One entry of the pattern: output row (a band), excitation bin and which light it holds.
struct RelightEntry {
  int32_t row = 0; ///< band index
  int32_t bin = 0; ///< excitation bin of the grid
  /// 1: the fluoresced part of the entry (row, bin) before it, kept where light of the bin
  /// reaches the band both reflected and re-radiated; 0: all light of (row, bin)
  int32_t fluoresced = 0;
  /// 1 when the bin overlaps the band's support, so that reflected light can reach it; 0: only
  /// re-radiated light can (unknown, 0, in files without the split: RelightLayers::split)
  int32_t diagonal = 0;
};

/// True when a and b are the same entry of a pattern.
inline bool sameEntry(const RelightEntry& a, const RelightEntry& b) {
  return a.row == b.row && a.bin == b.bin && a.fluoresced == b.fluoresced &&
         a.diagonal == b.diagonal;
}

/// The relightable part of a spectral image.
struct RelightLayers {
  RelightGrid grid;
  std::vector<RelightEntry> entries; ///< the pattern, ordered by row, bin, then part
  /// True when the entries tell reflected from fluoresced light (their diagonal flags and the
  /// fluoresced parts are known): the relit image then carries both components. Files written
  /// before the split hold only totals.
  bool split = false;
  /// The sources, in layer order: a light group's name, and NAME.2, NAME.3, ... for its further
  /// spectra (group names hold no dot)
  std::vector<std::string> sources;
  /// Per source, the bin averages (over the grid) of the spectrum its emitters were rendered
  /// with: relighting a group not given a new spectrum uses these.
  std::vector<std::vector<double>> spectra;
  /// Per source, the bin averages of each spectrum its fluorescent excitation was guided towards
  /// (a render told its relighting targets: one per target of its group, or the source's own
  /// spectrum for a group without targets); empty: none (the re-radiation matrices alone)
  std::vector<std::vector<std::vector<double>>> guides;
  /// [source][entry][pixel] transport means per unit emission spectrum
  std::vector<float> values;
  /// [source][entry][pixel] signed half-differences (A - B) / 2 of the two replicates' means:
  /// the variance of any linear combination c of the means is (c . d)^2
  std::vector<float> halfDifferences;

  /// True when the image holds a transport.
  bool present() const { return !sources.empty(); }
  /// Index of source `name`, or -1.
  int sourceIndex(const std::string& name) const;
  /// The light group source s belongs to (its name up to a dot).
  std::string groupOf(size_t s) const { return sources[s].substr(0, sources[s].find('.')); }
  /// The light groups, in order of their first source.
  std::vector<std::string> groups() const;
  /// Entries per source.
  size_t size() const { return entries.size(); }
};

} // namespace nx
