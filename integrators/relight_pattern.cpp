#include "integrators/relight_pattern.h"

#include <algorithm>
#include <bitset>

#include "spectra/reradiation_matrix.h"

namespace nx {
namespace {

using MatrixBins = std::bitset<ReradiationMatrix::kBins>;

// reach[o]: the 5 nm bins light can have left an emitter in to arrive in bin o, through any
// chain of the matrices (o itself: no re-radiation). Re-radiation only lengthens wavelengths
// (M[i][o] = 0 for o <= i), so one pass in increasing o closes the chains.
std::vector<MatrixBins> reachableExcitation(const RenderScene& scene) {
  std::vector<const ReradiationMatrix*> matrices;
  for (const Material& m : scene.materials)
    if (m.reradiation) matrices.push_back(m.reradiation.get());
  for (const HomogeneousMedium& m : scene.media)
    if (m.dye) matrices.push_back(m.dye.get());
  const int n = ReradiationMatrix::kBins;
  std::vector<MatrixBins> reach(static_cast<size_t>(n));
  for (int o = 0; o < n; ++o) {
    reach[static_cast<size_t>(o)].set(static_cast<size_t>(o));
    for (int i = 0; i < o; ++i)
      for (const ReradiationMatrix* m : matrices)
        if ((*m)(i, o) > 0) {
          reach[static_cast<size_t>(o)] |= reach[static_cast<size_t>(i)];
          break;
        }
  }
  return reach;
}

// The 5 nm matrix bins overlapping [lo, hi) nm.
MatrixBins matrixBinsOver(double lo, double hi) {
  MatrixBins b;
  for (int i = 0; i < ReradiationMatrix::kBins; ++i) {
    const double a = ReradiationMatrix::kMinNm + i * ReradiationMatrix::kBinNm;
    if (a < hi && a + ReradiationMatrix::kBinNm > lo) b.set(static_cast<size_t>(i));
  }
  return b;
}

} // namespace

RelightPattern::RelightPattern(const RelightGrid& grid, const Sensor& bands,
                               const RenderScene& scene)
    : grid_(grid), rows_(bands.count()) {
  const std::vector<MatrixBins> reach = reachableExcitation(scene);
  std::vector<MatrixBins> ofBin; // the matrix bins each relight bin overlaps
  for (int j = 0; j < grid.bins; ++j) ofBin.push_back(matrixBinsOver(grid.lo(j), grid.lo(j + 1)));
  for (int r = 0; r < rows_; ++r) {
    const double lo = bands.channel(r).lo, hi = bands.channel(r).hi;
    // Excitation bins any emission bin of the row's support can be reached from.
    MatrixBins excitation;
    const MatrixBins support = matrixBinsOver(lo, hi);
    for (int o = 0; o < ReradiationMatrix::kBins; ++o)
      if (support[static_cast<size_t>(o)]) {
        MatrixBins shifted = reach[static_cast<size_t>(o)];
        shifted.reset(static_cast<size_t>(o));
        excitation |= shifted;
      }
    for (int j = 0; j < grid.bins; ++j) {
      const bool diagonal = grid.lo(j) < hi && grid.lo(j + 1) > lo;
      const bool shifted = (excitation & ofBin[static_cast<size_t>(j)]).any();
      if (diagonal || shifted) entries_.push_back({r, j, 0, diagonal ? 1 : 0});
      if (diagonal && shifted) entries_.push_back({r, j, 1, 1});
    }
  }
  indexEntries();
}

RelightPattern::RelightPattern(const RelightGrid& grid, int rows, std::vector<RelightEntry> entries)
    : grid_(grid), rows_(rows), entries_(std::move(entries)) {
  indexEntries();
}

std::vector<double> binAverages(const Spectrum& s, const RelightGrid& grid) {
  constexpr int kPoints = 64;
  std::vector<double> out(static_cast<size_t>(grid.bins));
  for (int j = 0; j < grid.bins; ++j) {
    double sum = 0;
    for (int k = 0; k < kPoints; ++k) sum += s(grid.lo(j) + grid.stepNm * (k + 0.5) / kPoints);
    out[static_cast<size_t>(j)] = sum / kPoints;
  }
  return out;
}

void RelightPattern::indexEntries() {
  index_.assign(static_cast<size_t>(rows_) * static_cast<size_t>(grid_.bins), -1);
  fluorescedIndex_ = index_;
  for (size_t e = 0; e < entries_.size(); ++e)
    (entries_[e].fluoresced
         ? fluorescedIndex_
         : index_)[static_cast<size_t>(entries_[e].row) * grid_.bins + entries_[e].bin] =
        static_cast<int32_t>(e);
}

} // namespace nx
