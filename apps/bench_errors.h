#pragma once
// Errors of a render against a reference image, for the benchmark programs.

#include <vector>

#include "integrators/film.h"
#include "io/spectral_exr.h"

namespace nx::bench {

/// RMSE and relative RMSE (over the reference's mean) of the luminance Y, and the relative RMSE
/// of the bands (mean and worst over the bands; each band's RMSE kept).
struct ImageErrors {
  double rmseY = 0, relY = 0, meanBandRel = 0, maxBandRel = 0;
  std::vector<double> bandRmse;
};

/// The errors of a film covering the whole image against a reference of the same size and bands.
ImageErrors compareWithReference(const Film& f, const SpectralImage& ref);

} // namespace nx::bench
