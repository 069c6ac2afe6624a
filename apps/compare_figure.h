#pragma once
// nxcompare's figure: per-band error curves, region spectra of both sides, the spectral-angle
// map.

#include <string>

#include "spectra/cube_comparison.h"

namespace nx {

/// Writes the figure of `report` as a PNG (1200 pixels wide): per-band RMSE and bias against
/// wavelength, the mean spectra of up to six regions (render solid, capture dashed; the whole
/// compared area when there are no regions), and the spectral-angle map (black 0 degrees to
/// white at the 99th percentile, blue where there is no angle) of the width x height window.
void writeComparisonFigure(const std::string& path, const ComparisonReport& report, int width,
                           int height);

} // namespace nx
