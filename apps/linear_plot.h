#pragma once
// Line plots on linear axes drawn into a region of a canvas (nxcompare's figure panels).

#include "apps/plot_canvas.h"

namespace nx {

/// Draws the series on linear axes spanning all finite points (rounded out to "nice" ticks)
/// inside the rectangle (x, y, width, height) of the canvas, with grid, labels and legend.
void drawLinearPlot(Canvas& canvas, int x, int y, int width, int height,
                    const std::vector<PlotSeries>& series, const std::string& xLabel,
                    const std::string& yLabel, const std::string& title);

} // namespace nx
