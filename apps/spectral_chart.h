#pragma once
// A spectral test chart: Niixtracer's reflectances under several CIE illuminants. It stands
// in for scene rendering until the path tracer exists, and exercises the spectral library,
// the spectral EXR writer and the preview end to end.

#include "io/spectral_exr.h"

namespace nx {

/// Renders the chart (one row per illuminant, one column per reflectance name, `patch`
/// pixels square) with the given output bands; patches are computed in parallel.
SpectralImage renderSpectralChart(const SpectralBands& bands, int patch);

} // namespace nx
