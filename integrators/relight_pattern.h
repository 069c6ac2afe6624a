#pragma once
// Which (output row, excitation bin) pairs of a relightable render's transport can be non-zero:
// the diagonal (reflected light: bins inside a row's spectral support) and the pairs some chain
// of the scene's re-radiation matrices connects (fluoresced light). Where a diagonal pair can
// also be reached by re-radiation (a shift within the band, or within one bin), a second entry
// keeps its fluoresced part, so the transport splits exactly into reflected and fluoresced.

#include <vector>

#include "integrators/render_scene.h"
#include "io/relight_layers.h"
#include "spectra/sensor.h"

namespace nx {

/// The sparse pattern of a relightable render's transport.
class RelightPattern {
public:
  /// The pattern for `bands` (a row per band) on `grid`, given the re-radiation of the scene's
  /// materials and media.
  RelightPattern(const RelightGrid& grid, const Sensor& bands, const RenderScene& scene);
  /// The pattern of stored entries (an image read back).
  RelightPattern(const RelightGrid& grid, int rows, std::vector<RelightEntry> entries);

  const RelightGrid& grid() const { return grid_; }
  /// Output rows: the bands.
  int rows() const { return rows_; }
  /// The entries, ordered by row, bin, then part (RelightEntry).
  const std::vector<RelightEntry>& entries() const { return entries_; }
  /// Entries in all.
  int size() const { return static_cast<int>(entries_.size()); }
  /// Index of the pair (row, bin) among the entries, or -1 outside the pattern.
  int index(int row, int bin) const {
    return bin < 0 ? -1 : index_[static_cast<size_t>(row) * grid_.bins + bin];
  }
  /// Index of the fluoresced part of the diagonal pair (row, bin), or -1 where it has none.
  int fluorescedIndex(int row, int bin) const {
    return bin < 0 ? -1 : fluorescedIndex_[static_cast<size_t>(row) * grid_.bins + bin];
  }

private:
  void indexEntries();
  RelightGrid grid_;
  int rows_ = 0;
  std::vector<RelightEntry> entries_;
  std::vector<int32_t> index_;           ///< [row][bin]: all light of the pair
  std::vector<int32_t> fluorescedIndex_; ///< [row][bin]: its fluoresced part (diagonal pairs)
};

/// The averages of `s` over the bins of `grid` (midpoint rule, 64 points per bin: a line
/// spectrum tabulated at 1 nm is integrated to well within 1e-3).
std::vector<double> binAverages(const Spectrum& s, const RelightGrid& grid);

} // namespace nx
